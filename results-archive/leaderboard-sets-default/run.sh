#!/usr/bin/env bash
# Experiment C for every approximator with both learned sets and the default swing (seeds 0-4;
# docs/leaderboard.md, "The same with the default swing"). Resumable. Then: python3 compare.py
#   cargo build --release && bash results-archive/leaderboard-sets-default/run.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
./target/release/steplearn bench --approx lwpr,rbf,grid,kernel-ridge --rule pendulum-cart \
  --experiments stability --learn step-x,step-time --learn step-x,step-y,step-time \
  --seeds 5 --threads 1 --out results-archive/leaderboard-sets-default
