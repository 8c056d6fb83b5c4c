#!/usr/bin/env bash
# Regenerates the figures of docs/robot.md's "The humanoid" and "Closed loop on the humanoid"
# tables. Run from the repository root: bash results-archive/humanoid/run.sh
set -euo pipefail
out=results-archive/humanoid
cargo build --release --examples -p steplearn
cargo build --release -p steplearn-probes
run() { local name=$1; shift; echo "\$ $*" > "$out/$name.txt"; "$@" >> "$out/$name.txt" 2>&1; }
run stand ./target/release/examples/stand
run step_in_place ./target/release/examples/step_in_place
for x in -0.10 -0.05 0.05 0.10 0.15 0.20; do
  run "open_loop_default_$x" ./target/release/walk_open_loop --step-x=$x
done
for mu in 0.7 0.8 1.0; do
  for x in -0.100 -0.075 -0.050 -0.025 0.000 0.025 0.050 0.075 0.100 0.125 0.150 0.175 0.200; do
    run "open_loop_gait_mu${mu}_$x" ./target/release/walk_open_loop --gait open-loop --step-x=$x --friction $mu
  done
done
run open_loop_gait_in_place_60s ./target/release/walk_open_loop --gait open-loop --seconds 60
for f in -0.1 0.1 0.2; do
  run "capture_step_$f" ./target/release/walk --mode capture-step --step-x=$f --seconds 30
done
run capture_step_0.0_60s ./target/release/walk --mode capture-step --step-x=0 --seconds 60
run capture_step_0.0_300s ./target/release/walk --mode capture-step --step-x=0 --seconds 300
