#!/usr/bin/env python3
"""Prints each claim's first paired quantity over seeds 5-9 alone (the seeds that chose
nothing), from claims.json: mean, 95% Student-t interval, verdict. Ratios are averaged as
the main job averages them (mean of the per-seed ratios).

    python3 results-archive/paper/judge_seeds.py [DIR] [FIRST LAST]
"""
import json, math, statistics, sys

T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262}
d = sys.argv[1] if len(sys.argv) > 1 else "results-archive/paper"
first, last = (int(sys.argv[2]), int(sys.argv[3])) if len(sys.argv) > 3 else (5, 9)
claims = json.load(open(f"{d}/claims.json"))
for name in ["tracking", "disturbance", "stability", "robustness"]:
    q = claims[name]["over_seeds"][0]
    seeds = [s[0] for s in claims[name]["seeds"]]
    v = [x for s, x in zip(seeds, q["values"]) if first <= s <= last]
    m = statistics.mean(v)
    h = T975[len(v) - 1] * statistics.stdev(v) / math.sqrt(len(v))
    lo, hi = m - h, m + h
    better = (lo > q["null"]) if q["direction"] == "higher-is-better" else (hi < q["null"])
    worse = (hi < q["null"]) if q["direction"] == "higher-is-better" else (lo > q["null"])
    verdict = "better" if better else "worse" if worse else "level"
    print(f"{name}: {q['quantity']}, seeds {first}-{last}: {m:+.3f} [{lo:+.3f}, {hi:+.3f}] {verdict}")
