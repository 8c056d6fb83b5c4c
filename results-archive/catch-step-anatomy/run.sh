#!/bin/sh
# Per-push catch-step anatomy (catch_anatomy), experiment C's 400 pushes: dead zone 0 (the
# archived catch-step runs' learner) and 0.06 (the default; given explicitly, since a partial [settings.learner] table in a config file resets dead_zone to 0), seeds 0-1.
set -e
B=${B:-/work/wt-reach-target/release/catch_anatomy}
run() { # cfg direction seed
  flag=""; [ $2 = backward ] && flag=--backward
  [ -s $1-$2-s$3.csv ] || nice -n 10 $B --seed $3 $flag --config $1.toml --csv $1-$2-s$3.csv > $1-$2-s$3.txt
}
run dz0 forward 0
run dz06 forward 0
run dz0 backward 0
run dz06 backward 0
run dz0 forward 1
run dz06 forward 1
run dz0 backward 1
run dz06 backward 1
