#!/usr/bin/env bash
# The learned sole roll (`ankle-roll`) in experiment C: the model and the walker learning LEARN
# (default step-x,step-y,step-time,ankle-roll) with CONFIG (a file here; none: the defaults),
# pushed DIRS (default left and right, PUSHES pushes, default 200, the lateral levers' protocol)
# on SEEDS (default 0-4). Runs are named C-TAG-DIR-sS. `python3 table.py TAG...` pairs them by
# seed with step-x,step-y,step-time's runs on the same pushes (../lateral-levers sideways,
# ../leaderboard-sets-default forward).
#   cargo build --release && cd results-archive/ankle-roll
#   TAG=r1 bash run.sh                                       # the defaults (dead zone 0.06)
#   TAG=r2 CONFIG=dz0.toml bash run.sh                       # no dead zone on G_R
#   TAG=r3 CONFIG=dz02.toml bash run.sh                      # dead zone 0.02
#   TAG=r2 CONFIG=dz0.toml DIRS=forward PUSHES=400 bash run.sh   # pushed forward, the protocol
set -euo pipefail
bin=${BIN:-../../target/release/steplearn}
for s in ${SEEDS:-0 1 2 3 4}; do for dir in ${DIRS:-left right}; do
  out=C-$TAG-$dir-s$s
  [ -f $out/summary.json ] && continue
  $bin experiment stability --seed $s --push-direction $dir --pushes ${PUSHES:-200} \
    --learn ${LEARN:-step-x,step-y,step-time,ankle-roll} ${CONFIG:+--config $CONFIG} \
    --out $out > /dev/null
done; done
