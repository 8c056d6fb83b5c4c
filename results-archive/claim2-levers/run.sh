#!/usr/bin/env bash
# Claim 2 (experiment B) under learner settings: `bash run.sh NAME CONFIG SEED...` runs B for
# each seed into NAME-sS (CONFIG "-" = the defaults; the runs here are NAME.toml in this
# directory, base = the defaults) and keeps summary.json, disturbance_aligned.csv and
# run-config.toml. Build first: cargo build --release.
set -euo pipefail
bin=../../target/release/steplearn
name=$1; cfg=$2; shift 2
for s in "$@"; do
  out=$name-s$s
  [ -f $out/summary.json ] && continue
  args=(experiment disturbance --seed $s --out /tmp/claim2-$name-s$s --overwrite)
  [ "$cfg" != "-" ] && args+=(--config $cfg)
  $bin "${args[@]}" > /dev/null
  mkdir -p $out
  cp /tmp/claim2-$name-s$s/{summary.json,disturbance_aligned.csv,run-config.toml} $out/
done
