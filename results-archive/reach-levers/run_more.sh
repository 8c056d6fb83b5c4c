#!/bin/bash
cd /tmp/reach-levers
while kill -0 30678 2>/dev/null; do sleep 2; done
run() { # name outdir args...
  local OUT=$1; shift
  CMD="nice -n 10 /tmp/steplearn-fix experiment stability $* --pushes 200 --out $OUT"
  echo "$(date +%T) START $CMD" >> log.txt
  $CMD > /dev/null 2> $OUT.stderr
  echo "$(date +%T) END rc=$? $OUT" >> log.txt
}
run baseline-fwd-s0 --seed 0 --push-direction forward
run gain1.3-fwd-s0 --seed 0 --push-direction forward --config gain1.3.toml
for S in 0 1 2; do run gain1.3+lead0.05-s$S --seed $S --push-direction backward --config gain1.3+lead0.05.toml; done
