#!/usr/bin/env bash
# docs/reproducing.md: experiment D's impulse calibration. Pushes absorbed of 15, with and
# without learning, at 4-10 Ns, seeds 0-4. Run from the repository root; prints a table and
# keeps each run's summary.json.
set -euo pipefail
out=results-archive/robustness-impulse
tmp=$(mktemp -d)
for i in 4 5 6 8 10; do
  for s in 0 1 2 3 4; do
    ./target/release/steplearn experiment robustness --impulse-range $i,$i --seed $s --out "$tmp/D-${i}Ns-s$s" > /dev/null
    mkdir -p "$out/D-${i}Ns-s$s"
    cp "$tmp/D-${i}Ns-s$s/summary.json" "$out/D-${i}Ns-s$s/"
  done
done
rm -rf "$tmp"
python3 - "$out" > "$out/table.txt" <<'PY'
import json, sys
print("impulse (Ns) | learned: absorbed of 15, per seed 0-4 | first absorbed | without learning: falls of 15")
for i in [4, 5, 6, 8, 10]:
    a, f, n = [], [], []
    for s in range(5):
        d = json.load(open(f"{sys.argv[1]}/D-{i}Ns-s{s}/summary.json"))
        pushes = len(d["absorbed_by_push"])
        a.append(sum(d["absorbed_by_push"]))
        f.append(d["pushes_until_first_absorbed"])
        nl = d["no_learning"]
        n.append(nl.get("falls", nl))
    print(f"{i} | {' / '.join(map(str, a))} | {' / '.join(map(str, f))} | {' / '.join(map(str, n))}")
PY
cat "$out/table.txt"
