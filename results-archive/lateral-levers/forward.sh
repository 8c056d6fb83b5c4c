#!/usr/bin/env bash
# What the step time learned sideways costs pushed forward: C with the protocol's 400 pushes,
# seeds 0-4, --learn step-x,step-y,step-time with configs/frontal_step_time.toml, paired by
# forward.py with the same set's default runs in ../leaderboard-sets-default (lwpr).
set -euo pipefail
bin=../../target/release/steplearn
for s in 0 1 2 3 4; do
  out=C-forward-frontal-dz0-s$s
  [ -f $out/summary.json ] && continue
  $bin experiment stability --seed $s --learn step-x,step-y,step-time \
    --config ../../configs/frontal_step_time.toml --out $out &
  [ $((s % 2)) -eq 1 ] && wait
done
wait
