#!/bin/bash
# Runs catch_steps (C's protocol, 200 pushes) for each setting, seed and direction.
# Usage: run.sh "SEEDS" "SETTINGS"  (setting "base" = no config: the default swing, hip off)
cd /work/wt-hip2
D=results-archive/hip-strategy/rate
B=/work/tgt-hip2/release/catch_steps
for seed in $1; do for dir in forward backward; do for g in $2; do
  f=$D/${g}_s${seed}_${dir}.txt
  [ -s $f ] && continue
  extra=""; [ $dir = backward ] && extra="--backward"
  cfg=""; [ $g != base ] && cfg="--config $D/$g.toml"
  nice -n 10 $B --seed $seed --pushes 200 --learn step-x $extra $cfg > $f.tmp 2>&1 && mv $f.tmp $f
  echo "$g $seed $dir $(grep '^model' $f)" >> $D/summary.txt
done; done; done
