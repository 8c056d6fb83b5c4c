#!/usr/bin/env bash
# Learner levers with the default swing (docs/swing.md, "Learner levers with the default swing"):
# seeds 0-4, C with the protocol's 400 pushes, forward and backward, --learn step-x,step-time;
# default.toml is the default (the reference).
#   cargo build --release && cd results-archive/learner-levers && bash run.sh [LEVER ...]
# SEEDS="5 6 7 8 9" bash run.sh maxoff0.05 judges a lever on the seeds that chose nothing.
# LWPR's receptive-field width (2026-11-30, ninth session): bash run.sh lwprd3 lwprd30
# (BIN=path runs another binary).
set -euo pipefail
bin=${BIN:-../../target/release/steplearn}
levers=("$@"); [ ${#levers[@]} -eq 0 ] && levers=(default nofalls leak0.02 maxoff0.05 share0.5)
for lever in "${levers[@]}"; do
  for dir in forward backward; do for s in ${SEEDS:-0 1 2 3 4}; do
    out=C-$lever-$dir-s$s
    [ -f $out/summary.json ] && continue
    $bin experiment stability --seed $s --push-direction $dir \
      --learn step-x,step-time --config $lever.toml --out $out
  done; done
done
