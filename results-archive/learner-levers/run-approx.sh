#!/usr/bin/env bash
# The approximator as a lever (docs/swing.md, "Learner levers with the default swing"): kernel
# ridge, the closest to the model forward in results-archive/leaderboard-sets-default, pushed
# backward on seeds 0-4 (its forward runs are that leaderboard's), then both ways on seeds 5-9.
#   cargo build --release && cd results-archive/learner-levers && bash run-approx.sh [SEEDS]
set -euo pipefail
bin=../../target/release/steplearn
for s in ${1:-0 1 2 3 4}; do for dir in backward forward; do
  out=C-kernel-ridge-$dir-s$s
  [ -f $out/summary.json ] && continue
  if [ $dir = forward ] && [ $s -lt 5 ]; then continue; fi
  $bin experiment stability --approx kernel-ridge --seed $s --push-direction $dir \
    --learn step-x,step-time --out $out
done; done
