#!/usr/bin/env bash
# The learned sets on the judge seeds with the default swing since 2026-11-28 (steps that end at
# the landing, the tilt gain beyond its band, the tilted swing foot lifted): experiment C (the
# protocol's 400 pushes), seeds 5-9, forward and backward, the walker learning each set against
# the model on the same pushes. Then `python3 table.py > table.txt`.
#   cargo build --release && cd results-archive/judge-sets-landing && bash run.sh
set -euo pipefail
bin=../../target/release/steplearn
for set in step-x,step-time step-x,step-y,step-time; do
  for dir in forward backward; do for s in 5 6 7 8 9; do
    $bin experiment stability --seed $s --push-direction $dir --learn $set --out C-$set-$dir-s$s
  done; done
done
python3 table.py > table.txt
