#!/usr/bin/env bash
# Steps that end at the landing (docs/swing.md): every run of this directory.
#   cargo build --release && cd results-archive/landing-levers && bash run.sh
# Levers: seeds 0-2, C with 200 pushes, forward and backward (early0.2 backward only).
# Judge: configs/landing.toml (= gain1.3early0.5.toml) on seeds 5-9, C's 400 pushes; its
# default runs are ../catch-step-reach/C-step-x_step-time-*.
set -euo pipefail
bin=../../target/release/steplearn
for lever in default wait0.1 early0.5 early0.5wait0.1 gain1.3early0.5; do
  for dir in forward backward; do for s in 0 1 2; do
    $bin experiment stability --seed $s --push-direction $dir --pushes 200 \
      --learn step-x,step-time --config $lever.toml --out xt-$lever-$dir-s$s
  done; done
done
for s in 0 1 2; do
  $bin experiment stability --seed $s --push-direction backward --pushes 200 \
    --learn step-x,step-time --config early0.2.toml --out xt-early0.2-backward-s$s
done
# The tilted swing lifted higher, with the landing config.
for lever in lift0.3 lift0.6; do for dir in backward forward; do for s in 0 1 2; do
  $bin experiment stability --seed $s --push-direction $dir --pushes 200 \
    --learn step-x,step-time --config $lever.toml --out xt-$lever-$dir-s$s
done; done; done
for dir in backward forward; do for s in 5 6 7 8 9; do
  $bin experiment stability --seed $s --push-direction $dir --learn step-x,step-time \
    --config ../../configs/landing.toml --out judge-$dir-s$s
done; done
for dir in backward forward; do for s in 5 6 7 8 9; do
  $bin experiment stability --seed $s --push-direction $dir --learn step-x,step-time \
    --config lift0.3.toml --out judge-lift0.3-$dir-s$s
done; done
# 2026-11-28: the tilt gain 1.3 biases undisturbed walking (undisturbed.txt); the tilt gain
# beyond a band (tilt_gain_band), and early landing with the lift at gain 1, seeds 0-2, then the
# band's candidates and the reference on seeds 3-4 as well.
for lever in early0.5lift0.3 band0.02 band0.05; do for dir in backward forward; do for s in 0 1 2; do
  $bin experiment stability --seed $s --push-direction $dir --pushes 200 \
    --learn step-x,step-time --config $lever.toml --out xt-$lever-$dir-s$s
done; done; done
for lever in default band0.02 band0.05; do for dir in backward forward; do for s in 3 4; do
  $bin experiment stability --seed $s --push-direction $dir --pushes 200 \
    --learn step-x,step-time --config $lever.toml --out xt-$lever-$dir-s$s
done; done; done
(cd ../.. && cargo run --release -p steplearn-probes --bin undisturbed_steps -- 1,1,0,0 \
  0.5,1.0,0.3,0 0.5,1.3,0.3,0 0.5,1.3,0.3,0.02 0.5,1.3,0.3,0.05 1,1.3,0,0) > undisturbed.txt
SEEDS=0,1,2,3,4 python3 levers.py default band0.02 band0.05 > levers-band.txt
# The default (band0.05.toml) with a wider step range for both walkers, seeds 0-4.
for dir in backward forward; do for s in 0 1 2 3 4; do
  $bin experiment stability --seed $s --push-direction $dir --pushes 200 \
    --learn step-x,step-time --config wide0.6.toml --out xt-wide0.6-$dir-s$s
done; done
SEEDS=0,1,2,3,4 python3 levers.py band0.05 wide0.6 > levers-wide.txt
python3 levers.py > levers.txt
python3 judge.py > judge.txt
python3 judge.py judge-lift0.3 > judge-lift0.3.txt
# The trace of one backward push on seed 0 (push 67 at 245.27 s), model walker, defaults:
(cd ../.. && cargo run --release -p steplearn-probes --bin catch_anatomy -- --seed 0 --backward \
  --learn step-x --csv /dev/null --trace 245.20 245.60) | grep '^t ' > trace-backward-s0.txt
# The per-push anatomy of seed 0 backward, defaults (lib_ columns: the library's catch step):
(cd ../.. && cargo run --release -p steplearn-probes --bin catch_anatomy -- --seed 0 --backward \
  --learn step-x --csv results-archive/landing-levers/anatomy-backward-s0.csv) > /dev/null
python3 anatomy.py anatomy-backward-s0.csv > anatomy.txt
# The same with configs/landing.toml:
(cd ../.. && cargo run --release -p steplearn-probes --bin catch_anatomy -- --seed 0 --backward \
  --learn step-x --config configs/landing.toml \
  --csv results-archive/landing-levers/anatomy-backward-s0-landing.csv) > /dev/null
python3 anatomy.py anatomy-backward-s0-landing.csv > anatomy-landing.txt
