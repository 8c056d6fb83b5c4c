#!/usr/bin/env bash
# Second round: a wider grid forward with 45 null pairs of +-0.2 mm steps (up to +-4.4 mm) as
# the chaos envelope, the same grid held over the catch step only (0.4 s) and for 2 s, and the
# backward chaos envelope of the first round's grid. Run from the repository root.
set -euo pipefail
out=results-archive/offset-oracle
cargo build --release -p steplearn-probes --bin offset_oracle
o=./target/release/offset_oracle
dx=-0.2,-0.15,-0.1,-0.05,0,0.05,0.1,0.15,0.2
dt=-0.15,-0.1,-0.05,0,0.05
$o --cases 100 --direction backward --impulse 8,24 --dx 0 --dt 0 --chaos 20 --chaos-step 2e-4 > $out/backward-chaos.csv
$o --cases 100 --direction forward --impulse 12,32 --dx $dx --dt $dt --hold 1.0 --chaos 45 --chaos-step 2e-4 > $out/forward-wide-hold1.0.csv
$o --cases 100 --direction forward --impulse 12,32 --dx $dx --dt $dt --hold 0.4 --chaos 0 > $out/forward-wide-hold0.4.csv
$o --cases 100 --direction forward --impulse 12,32 --dx $dx --dt $dt --hold 2.0 --chaos 0 > $out/forward-wide-hold2.0.csv
