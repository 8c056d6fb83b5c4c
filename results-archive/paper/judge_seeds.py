#!/usr/bin/env python3
"""Prints each claim's first paired quantity over seeds 5-9 alone (the seeds that chose
nothing), from claims.json: mean, 95% Student-t interval, verdict. Ratios are averaged as
the main job averages them (mean of the per-seed ratios).

    python3 results-archive/paper/judge_seeds.py [DIR] [FIRST LAST]
"""
import json, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from paired import mean_h  # noqa: E402
d = sys.argv[1] if len(sys.argv) > 1 else "results-archive/paper"
first, last = (int(sys.argv[2]), int(sys.argv[3])) if len(sys.argv) > 3 else (5, 9)
claims = json.load(open(f"{d}/claims.json"))
for name in ["tracking", "disturbance", "stability", "robustness"]:
    q = claims[name]["over_seeds"][0]
    seeds = [s[0] for s in claims[name]["seeds"]]
    v = [x for s, x in zip(seeds, q["values"]) if first <= s <= last]
    m, h = mean_h(v)
    lo, hi = m - h, m + h
    better = (lo > q["null"]) if q["direction"] == "higher-is-better" else (hi < q["null"])
    worse = (hi < q["null"]) if q["direction"] == "higher-is-better" else (lo > q["null"])
    verdict = "better" if better else "worse" if worse else "level"
    print(f"{name}: {q['quantity']}, seeds {first}-{last}: {m:+.3f} [{lo:+.3f}, {hi:+.3f}] {verdict}")
