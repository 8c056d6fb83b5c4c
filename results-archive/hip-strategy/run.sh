#!/bin/bash
# Runs catch_steps (C's protocol, 200 pushes) for each hip_gain, seed and direction.
cd /work/wt-hip
D=results-archive/hip-strategy
B=/work/wt-hip-target/release/catch_steps
for seed in 0 1; do for dir in forward backward; do for g in 0 1 -1; do
  f=$D/g${g}_s${seed}_${dir}.txt
  [ -s $f ] && continue
  extra=""; [ $dir = backward ] && extra="--backward"
  nice -n 19 $B --seed $seed --pushes 200 --learn step-x $extra --config $D/hip_$g.toml > $f.tmp 2>&1 && mv $f.tmp $f
  echo "$g $seed $dir $(grep '^model' $f)" >> $D/summary.txt
done; done; done
