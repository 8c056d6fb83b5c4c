#!/bin/sh
# Experiment C (400 pushes, the default tracking swing and dead zone) on seeds 5-9, forward and
# backward, with the catch step's command as the touch-down now records it (the command the
# swing foot was let go at, also where the generator exchanged its legs before the estimator
# saw the touch-down). Learned sets: step-x (the default) and step-x,step-time.
# Run from this directory: S=path/to/steplearn sh run.sh
set -e
S=${S:-../../target/release/steplearn}
for set in step-x step-x,step-time; do
  for d in forward backward; do
    for s in 5 6 7 8 9; do
      out=C-$(echo $set | tr , _)-$d-s$s
      [ -s $out/summary.json ] || nice -n 10 $S experiment stability --seed $s --push-direction $d --learn $set --out $out > /dev/null
    done
  done
done
