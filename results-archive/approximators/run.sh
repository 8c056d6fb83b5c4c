#!/usr/bin/env bash
# docs/approximators.md: LWPR on the cross 2D and 3-input problems, and every approximator on
# the same seeded streams. Run from the repository root. Times are wall clock on whatever the
# machine is doing; accuracy, field counts and file sizes are deterministic.
set -euo pipefail
out=results-archive/approximators
cargo build --release --example lwpr_cross -p steplearn
cargo build --release -p steplearn-probes --bin compare_approximators
./target/release/examples/lwpr_cross > "$out/lwpr_cross.txt" 2>&1
./target/release/compare_approximators > "$out/compare_approximators.txt" 2>&1
