#!/usr/bin/env python3
"""C, seeds 0-4: a shorter shortest step (msd25: min_step_duration 0.25 s, msd20: 0.2 s) against
the defaults (0.3 s, ../learner-levers/C-default-*), the model and the walker learning
step-x,step-time on the same pushes. Run: python3 table.py [TAG...] (from anywhere)."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
os.chdir(HERE)
sys.path.insert(0, os.path.dirname(HERE))
from paired import i50, interval, ratio, summary  # noqa: E402

tags = sys.argv[1:] or ["msd25", "msd20"]
KEYS = ["catch_step_clamped", "later_step_clamped", "tipped_after_catch_step"]
print("| setting | pushes | model / default model | learned / model | learned / default learned | model reach | falls: model (catch clamped, later clamped, tipped) | learned |")
print("|---|---|---|---|---|---|---|---|")
for tag in ["default"] + tags:
    for d in ["forward", "backward"]:
        runs = [(f"C-{tag}-{d}-s{s}" if tag != "default" else f"../learner-levers/C-default-{d}-s{s}",
                 f"../learner-levers/C-default-{d}-s{s}") for s in range(5)]
        runs = [(a, b) for a, b in runs if os.path.exists(os.path.join(a, "summary.json"))]
        if not runs:
            continue
        mm, lm, ll, reach = [], [], [], []
        falls = {"model": [0] * 3, "learned": [0] * 3}
        for a, b in runs:
            sa, sb = summary(a), summary(b)
            mm.append(i50(sa, "model") / i50(sb, "model"))
            lm.append(ratio(sa))
            ll.append(i50(sa, "learned") / i50(sb, "learned"))
            reach.append(sa["catch_step_reach"]["model"])
            for w in falls:
                falls[w] = [x + sa["fall_causes"][w][k] for x, k in zip(falls[w], KEYS)]
        print(f"| {tag} (n={len(runs)}) | {d} | {interval(mm)} | {interval(lm)} | {interval(ll)} | "
              f"{sum(reach) / len(reach):.3f} | {falls['model']} | {falls['learned']} |")
