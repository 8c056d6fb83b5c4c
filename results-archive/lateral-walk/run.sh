#!/usr/bin/env bash
# docs/lateral.md: the model walking sideways and diagonally (walk probe, 30 s each), and the
# coupled learner's side push test. Run from the repository root.
set -euo pipefail
out=results-archive/lateral-walk
cargo build --release -p steplearn-probes --bin walk
for xy in "0 0.04" "0 -0.04" "0.1 0.04" "0.2 0.06"; do
  set -- $xy
  echo "\$ walk --step-x=$1 --step-y=$2 --seconds 30" > "$out/walk_$1_$2.txt"
  ./target/release/walk --step-x=$1 --step-y=$2 --seconds 30 >> "$out/walk_$1_$2.txt" 2>&1
done
cargo test --release --test all coupled::on_the_humanoid -- --nocapture > "$out/coupled_side_push.txt" 2>&1
