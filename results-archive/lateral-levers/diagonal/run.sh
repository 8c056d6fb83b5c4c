#!/usr/bin/env bash
# C pushed from the omnidirectional experiment's other sectors (200 pushes, seeds 0-4 unless
# SEEDS is set), the walker learning step-x,step-y,step-time with CONFIG (default: the step
# time in both planes, configs/both_planes_step_time.toml), runs named NAME (default both-dz0):
#   bash run.sh [CONFIG NAME [AZIMUTH ...]]     azimuths in degrees, default 45 135 180 225 315
set -euo pipefail
bin=../../../target/release/steplearn
config=${1:-../../../configs/both_planes_step_time.toml}
name=${2:-both-dz0}
shift $(( $# < 2 ? $# : 2 ))
azimuths=("$@"); [ ${#azimuths[@]} -eq 0 ] && azimuths=(45 135 180 225 315)
for az in "${azimuths[@]}"; do for s in ${SEEDS:-0 1 2 3 4}; do
  out=C-$name-az$az-s$s
  [ -f $out/summary.json ] && continue
  $bin experiment stability --seed $s --pushes 200 --push-direction $az \
    --learn step-x,step-y,step-time --config $config --out $out
done; done
