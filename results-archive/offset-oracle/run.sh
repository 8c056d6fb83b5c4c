#!/usr/bin/env bash
# The offset oracle (probes/src/bin/offset_oracle.rs): one push per case, the model against every
# constant (dF, dT) pair of the grid held from the push, and the chaos envelope.
# Run from the repository root: bash results-archive/offset-oracle/run.sh [hold]
set -euo pipefail
hold=${1:-1.0}
out=results-archive/offset-oracle
cargo build --release -p steplearn-probes --bin offset_oracle
./target/release/offset_oracle --cases 100 --direction forward --impulse 12,32 --hold "$hold" > "$out/forward-hold$hold.csv"
./target/release/offset_oracle --cases 100 --direction backward --impulse 8,24 --hold "$hold" > "$out/backward-hold$hold.csv"
