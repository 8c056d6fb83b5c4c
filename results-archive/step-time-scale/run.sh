#!/usr/bin/env bash
# The table "learned set / S / I50 / dT at the catch step ..." in docs/learner.md ("The
# step-time gradient"): experiment C's protocol, seed 0, 200 forward pushes.
# Run from the repository root: bash results-archive/step-time-scale/run.sh
set -euo pipefail
out=results-archive/step-time-scale
cargo build --release -p steplearn-probes --bin catch_steps
run() { local name=$1; shift; echo "\$ $*" > "$out/$name.txt"; "$@" >> "$out/$name.txt" 2>&1; }
run step-x ./target/release/catch_steps --seed 0 --pushes 200 --learn step-x
run step-time ./target/release/catch_steps --seed 0 --pushes 200 --learn step-time
for s in 1 0.3 0.1; do
  run "step-x,step-time-S$s" ./target/release/catch_steps --seed 0 --pushes 200 --learn step-x,step-time --time-scale $s
done
