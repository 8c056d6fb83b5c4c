#!/usr/bin/env bash
# The ankle strategy on the model (`[settings.walker.motion] ankle_gain`): single-push I50 over
# cases 0-99 (offset_oracle with the null grid: the model and the (0, 0) pair, which is the model)
# for each gain's config, forward and backward. Run from the repository root.
set -euo pipefail
out=results-archive/ankle-strategy
cargo build --release -p steplearn-probes --bin offset_oracle
o=./target/release/offset_oracle
for g in ${GAINS:-base -1 -0.5 -0.2 0.2 0.5 1}; do
  cfg=(); [ "$g" != base ] && cfg=(--config "$out/a$g.toml")
  $o --cases 100 --direction forward --impulse 12,32 --dx 0 --dt 0 --chaos 0 "${cfg[@]}" > "$out/forward-$g.csv"
  $o --cases 100 --direction backward --impulse 8,24 --dx 0 --dt 0 --chaos 0 "${cfg[@]}" > "$out/backward-$g.csv"
  echo "$g forward $(grep '^model' "$out/forward-$g.csv") backward $(grep '^model' "$out/backward-$g.csv")"
done
