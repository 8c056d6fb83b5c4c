#!/usr/bin/env bash
# The spread of the pendulum-cart gradient G = theta_E - 0.15 tanh(30 F_E) at the touch-downs of
# experiment A's model (seeds 0-4, every step after the first 5 s), the rationale of the dead
# zone in docs/learner.md. Run from the repository root; writes g_spread.txt beside this file.
set -euo pipefail
here=results-archive/dead-zone-choice
tmp=$(mktemp -d)
for s in 0 1 2 3 4; do
  ./target/release/steplearn experiment tracking --seed $s --out "$tmp/A-s$s" > /dev/null
done
python3 - "$tmp" > "$here/g_spread.txt" <<'PY'
import csv, math, statistics, sys
print("seed touch-downs median|G| p90|G| std(G) share|G|>0.06")
for s in range(5):
    g = []
    for r in csv.DictReader(open(f"{sys.argv[1]}/A-s{s}/tracking_steps.csv")):
        if r["controller"] != "model" or float(r["time_s"]) < 5.0:
            continue
        g.append(float(r["theta_e_rad"]) - 0.15 * math.tanh(30.0 * float(r["f_e_m"])))
    a = sorted(abs(x) for x in g)
    p90 = a[int(0.9 * (len(a) - 1))]
    share = sum(x > 0.06 for x in a) / len(a)
    print(f"{s} {len(g)} {statistics.median(a):.3f} {p90:.3f} {statistics.pstdev(g):.3f} {share:.2f}")
PY
rm -rf "$tmp"
