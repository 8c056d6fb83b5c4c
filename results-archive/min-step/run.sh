#!/usr/bin/env bash
# Experiment C (the protocol's 400 pushes) forward and backward with a shorter shortest step
# for both walkers, the model and the walker learning step-x,step-time on the same pushes.
# Seeds 0-4 pair with ../learner-levers/C-default-* (the defaults, same learner).
#   cargo build --release && cd results-archive/min-step
#   TAG=msd25 SEEDS="0 1 2 3 4" bash run.sh;  TAG=msd20 SEEDS="0 1 2 3 4" bash run.sh
# BIN=path runs another binary; JOBS runs that many at once (default 2).
set -euo pipefail
bin=${BIN:-../../target/release/steplearn}
for s in ${SEEDS:-0 1 2 3 4}; do for dir in ${DIRS:-forward backward}; do
  out=C-$TAG-$dir-s$s
  [ -f $out/summary.json ] && continue
  echo "$bin experiment stability --seed $s --push-direction $dir --learn step-x,step-time --config $TAG.toml --out $out"
done; done | xargs -P ${JOBS:-2} -I{} sh -c '{} > /dev/null'
