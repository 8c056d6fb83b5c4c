#!/usr/bin/env bash
# The ankle strategy (gain 1.0, chosen on the single-push cases 0-99) in experiment C (the
# protocol's 400 pushes), forward and backward, --learn step-x,step-time: the model and the
# learner with it. Seeds 0-4 pair with ../learner-levers/C-default-*, seeds 5-9 with
# ../judge-sets-landing/C-step-x,step-time-* (the defaults, same pushes); `python3 table.py`.
#   cargo build --release && cd results-archive/ankle-strategy && SEEDS="0 1 2 3 4" bash run-c.sh
set -euo pipefail
bin=../../target/release/steplearn
for s in ${SEEDS:-0 1 2 3 4}; do for dir in forward backward; do
  out=C-a1-$dir-s$s
  [ -f $out/summary.json ] && continue
  $bin experiment stability --seed $s --push-direction $dir --learn step-x,step-time \
    --config a1.toml --out $out > /dev/null
done; done
