#!/usr/bin/env bash
# What a step time learned sideways costs pushed forward: C with the protocol's 400 pushes,
# seeds 0-4, --learn step-x,step-y,step-time with CONFIG (default
# configs/frontal_step_time.toml, runs named NAME, default frontal-dz0), paired by forward.py
# with the same set's default runs in ../leaderboard-sets-default (lwpr).
#   bash forward.sh [CONFIG NAME]   e.g. bash forward.sh ../../configs/both_planes_step_time.toml both-dz0
set -euo pipefail
bin=${BIN:-../../target/release/steplearn}
config=${1:-../../configs/frontal_step_time.toml}
name=${2:-frontal-dz0}
for s in ${SEEDS:-0 1 2 3 4}; do
  out=C-forward-$name-s$s
  [ -f $out/summary.json ] && continue
  $bin experiment stability --seed $s --learn step-x,step-y,step-time \
    --config $config --out $out
done
