#!/bin/sh
# The W6 lever of results-archive/step-time-levers (wider step range) with the dead zone 0.06
# it was meant to have: its configs/W6.toml ran with dead_zone = 0 (see its run-config.toml).
set -e
S=${S:-/work/wt-reach-target/release/steplearn}
for d in forward backward; do for s in 0 1 2 3 4; do
  [ -s C-W6dz06-$d-s$s/summary.json ] || nice -n 10 $S experiment stability --seed $s --push-direction $d --pushes 200 --config W6-dz06.toml --out C-W6dz06-$d-s$s > /dev/null
done; done
