#!/usr/bin/env bash
# docs/learner.md: stepping in place 60 s, the model and the learner (the stagger of the feet),
# and the toy sagittal walker's test output. Run from the repository root.
set -euo pipefail
out=results-archive/stepping-in-place
cargo build --release -p steplearn-probes --bin walk
./target/release/walk --seconds 60 > "$out/model-60s.txt" 2>&1
./target/release/walk --seconds 60 --learn > "$out/learned-60s.txt" 2>&1
cargo test --release --test all learner::learning_reduces_trunk_and_step_errors_on_a_toy_walker -- --nocapture > "$out/toy-walker.txt" 2>&1
