#!/usr/bin/env bash
# Third round: the first round's grid (hold 1 s) with the gait phase at each push, on cases
# 0-99 (which choose a reflex's pair per phase and impulse bin) and 100-199 (which judge it;
# `python3 oracle.py reflex`). Run from the repository root.
set -euo pipefail
out=results-archive/offset-oracle
cargo build --release -p steplearn-probes --bin offset_oracle
o=./target/release/offset_oracle
for first in 0 100; do
  $o --cases 100 --first-case $first --direction backward --impulse 8,24 --chaos 0 > $out/backward-phase-c$first.csv
  $o --cases 100 --first-case $first --direction forward --impulse 12,32 --chaos 0 > $out/forward-phase-c$first.csv
done
