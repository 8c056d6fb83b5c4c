#!/usr/bin/env bash
# The learned sole pitch in experiment C (the protocol's 400 pushes), forward and backward:
# the model and the walker learning TAG's set. Seeds 0-4 pair with ../learner-levers/C-default-*,
# seeds 5-9 with ../judge-sets-landing/C-step-x,step-time-* (step-x,step-time with the
# defaults, same pushes); `python3 table.py TAG...` prints the table.
#   cargo build --release && cd results-archive/ankle-pitch
#   TAG=v1 LEARN=step-x,step-time,ankle-pitch SEEDS="0 1 2 3 4" bash run.sh
#   TAG=v2 LEARN=step-x,step-time,ankle-pitch CONFIG=m05.toml SEEDS="0 1 2 3 4" bash run.sh
#   TAG=v3 LEARN=step-x,step-time,ankle-pitch CONFIG=dz02.toml SEEDS="0 1 2 3 4" bash run.sh
#   TAG=v4 LEARN=step-x,step-time,ankle-pitch CONFIG=leak01.toml SEEDS="0 1 2 3 4" bash run.sh
#   TAG=v1 LEARN=step-x,step-time,ankle-pitch SEEDS="5 6 7 8 9" bash run.sh
# The pitch on its heel alone (BIN=path runs another binary):
#   TAG=h1 LEARN=step-x,step-time,ankle-pitch CONFIG=heel.toml SEEDS="0 1 2 3 4" bash run.sh
#   TAG=h2 LEARN=step-x,step-time,ankle-pitch CONFIG=heel-dz02.toml SEEDS="0 1 2 3 4 5 6 7 8 9" bash run.sh
#   TAG=h2 LEARN=step-x,step-time,ankle-pitch CONFIG=heel-dz02.toml SEEDS="10 11 12 13 14" bash run.sh
#   TAG=xt LEARN=step-x,step-time SEEDS="10 11 12 13 14" DIRS=backward bash run.sh
#   TAG=h3 LEARN=step-x,step-time,ankle-pitch CONFIG=heel-dz04.toml SEEDS="0 1 2 3 4" bash run.sh
#   TAG=h4 LEARN=step-x,step-time,ankle-pitch CONFIG=heel-dz02-leak01.toml SEEDS="0 1 2 3 4" bash run.sh
# A sooner-only step time (offset_range on step-time), with and without the heel, and the toe
# alone pushed forward (2026-11-30, ninth session):
#   TAG=s1 LEARN=step-x,step-time CONFIG=sooner.toml SEEDS="0 1 2 3 4" bash run.sh
#   TAG=hs LEARN=step-x,step-time,ankle-pitch CONFIG=heel-sooner.toml SEEDS="0 1 2 3 4" bash run.sh
#   TAG=t1 LEARN=step-x,step-time,ankle-pitch CONFIG=toe.toml SEEDS="0 1 2 3 4" DIRS=forward bash run.sh
# The heel gated by the fall (gate = "with-the-fall", ninth session):
#   TAG=hg LEARN=step-x,step-time,ankle-pitch CONFIG=heel-gated.toml SEEDS="0 1 2 3 4 5 6 7 8 9" bash run.sh
# The pitch both ways gated by the fall (tenth session):
#   TAG=bg LEARN=step-x,step-time,ankle-pitch CONFIG=both-gated.toml SEEDS="0 1 2 3 4" bash run.sh
#   TAG=xt LEARN=step-x,step-time SEEDS="10 11 12 13 14" DIRS=forward bash run.sh
set -euo pipefail
bin=${BIN:-../../target/release/steplearn}
for s in ${SEEDS:-0 1 2 3 4}; do for dir in ${DIRS:-backward forward}; do
  out=C-$TAG-$dir-s$s
  [ -f $out/summary.json ] && continue
  $bin experiment stability --seed $s --push-direction $dir --learn $LEARN \
    ${CONFIG:+--config $CONFIG} --out $out > /dev/null
done; done
