#!/bin/sh
# Per-push catch-step anatomy, seeds 0-1, forward and backward, dead zone 0 and the default.
set -e
B=${B:-/work/wt-reach-target/release/catch_anatomy}
for cfg in dz0 default; do for s in 0 1; do for d in forward backward; do
  flag=""; [ $d = backward ] && flag=--backward
  nice -n 10 $B --seed $s $flag --config $cfg.toml --csv $cfg-$d-s$s.csv > $cfg-$d-s$s.txt
done; done; done
