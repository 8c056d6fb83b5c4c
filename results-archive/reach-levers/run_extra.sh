#!/bin/bash
cd /tmp/reach-levers
for L in gain1.45 gain1.15; do for S in 0 1 2; do
  CMD="nice -n 10 /tmp/steplearn-fix experiment stability --seed $S --push-direction backward --pushes 200 --config $L.toml --out $L-s$S"
  echo "$(date +%T) START $CMD" >> log.txt
  $CMD > /dev/null 2> $L-s$S.stderr
  echo "$(date +%T) END rc=$? $L-s$S" >> log.txt
done; done
