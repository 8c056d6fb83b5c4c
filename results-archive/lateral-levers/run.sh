#!/usr/bin/env bash
# Lateral levers with the default swing (docs/lateral.md, "Sideways with the default swing"):
# C pushed left and right (200 pushes), seeds 0-4 unless SEEDS is set; each LEVER is
# SET:CONFIG, the learned set and a config in this directory (default.toml: no change).
#   cargo build --release && cd results-archive/lateral-levers && bash run.sh [SET:CONFIG ...]
set -euo pipefail
bin=${BIN:-../../target/release/steplearn}
levers=("$@"); [ ${#levers[@]} -eq 0 ] && levers=(step-x,step-y,step-time:default step-y:default)
for lever in "${levers[@]}"; do
  set_=${lever%%:*}; cfg=${lever#*:}
  for dir in left right; do for s in ${SEEDS:-0 1 2 3 4}; do
    out=C-${set_//,/+}-$cfg-$dir-s$s
    [ -f $out/summary.json ] && continue
    $bin experiment stability --seed $s --pushes 200 --push-direction $dir \
      --learn $set_ --config $cfg.toml --out $out
  done; done
done
