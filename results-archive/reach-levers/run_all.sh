#!/bin/bash
cd /tmp/reach-levers
for L in baseline gain1.3 lead0.05 gain1.6; do
 for S in 0 1 2; do
  if [ $L = baseline ]; then CFG=""; else CFG="--config $L.toml"; fi
  CMD="nice -n 10 /tmp/steplearn-fix experiment stability --seed $S --push-direction backward --pushes 200 $CFG --out $L-s$S"
  echo "$(date +%T) START $CMD" >> log.txt
  $CMD > /dev/null 2> $L-s$S.stderr
  echo "$(date +%T) END rc=$? $L-s$S" >> log.txt
 done
done
