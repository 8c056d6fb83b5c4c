#!/usr/bin/env bash
# LWPR speed against the reference C library (docs/performance.md, "LWPR against the C library"):
# three interleaved runs of steplearn's `lwpr_cross` example and of the C timing driver
# benches/reference/lwpr_c_timing.c, built against a checkout of github.com/ipab-slmc/lwpr.
#   LWPR_C=/path/to/lwpr bash results-archive/timings/lwpr-vs-c.sh > results-archive/timings/lwpr-vs-c.txt
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
: "${LWPR_C:?set LWPR_C to a checkout of github.com/ipab-slmc/lwpr}"
build=$(mktemp -d)
printf '#define HAVE_LIBM 1\n#define LIBRARY_API\n' > "$LWPR_C/include/lwpr_config.h"
gcc -O2 -I"$LWPR_C/include" -o "$build/lwpr_c_timing" "$root/benches/reference/lwpr_c_timing.c" \
    "$LWPR_C"/src/{lwpr.c,lwpr_aux.c,lwpr_math.c,lwpr_mem.c,lwpr_binio.c} -lm
(cd "$root" && cargo build --release --example lwpr_cross >/dev/null 2>&1)
echo "# $(date -u +%FT%TZ) $(uname -m) $(nproc) cores; gcc $(gcc -dumpversion); steplearn $(git -C "$root" rev-parse --short HEAD)"
for run in 1 2 3; do
    echo "## run $run: steplearn (cargo run --release --example lwpr_cross)"
    "$root/target/release/examples/lwpr_cross"
    echo "## run $run: C library (benches/reference/lwpr_c_timing.c, gcc -O2)"
    "$build/lwpr_c_timing"
done
