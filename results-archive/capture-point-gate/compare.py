#!/usr/bin/env python3
"""C pushed forward, seeds 0-4: RBF and the grid learning step-x,step-time with the sole's pitch on
its heel alone, gated by the capture point (capture-point/, the probe binary of
capture-point.patch) and by the rate (rate/, `gate = "with-the-fall"` as built), learned / model
paired by seed, beside the same approximator learning step-x,step-time alone on the same pushes
(../leaderboard-sets-default). Run: python3 compare.py (from anywhere)."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
os.chdir(HERE)
sys.path.insert(0, os.path.dirname(HERE))
from paired import i50, interval, ratio, summary  # noqa: E402

print("| approximator | capture-point gate | rate gate (with-the-fall) | step-x,step-time alone | capture point - rate |")
print("|---|---|---|---|---|")
for approx in ["rbf", "grid"]:
    def name(s, learn="step-x+step-time+ankle-pitch"):
        return f"stability__{approx}__pendulum-cart__s{s}__{learn}"
    cols = [[f"capture-point/{name(s)}" for s in range(5)],
            [f"rate/{name(s)}" for s in range(5)],
            [f"../leaderboard-sets-default/{name(s, 'step-x+step-time')}" for s in range(5)]]
    sums = [[summary(d) for d in runs] for runs in cols]
    for col in sums[1:]:
        assert all(i50(a, "model") == i50(b, "model") for a, b in zip(sums[0], col)), "the model differs"
    ratios = [[ratio(s) for s in col] for col in sums]
    diff = [a - b for a, b in zip(ratios[0], ratios[1])]
    print(f"| {approx} | " + " | ".join(interval(r) for r in ratios) + f" | {interval(diff)} |")

print()
print("Falls of the learned walker summed over seeds 0-4 (the model's in the last row per approximator):")
KEYS = ["before_touch_down", "catch_step_clamped", "later_step_clamped", "tipped_after_catch_step"]
print("| approximator | walker | " + " | ".join(KEYS) + " |")
print("|---|---|" + "---|" * len(KEYS))
for approx in ["rbf", "grid"]:
    for label, where, learn, walker in [
            ("capture-point gate", "capture-point", "step-x+step-time+ankle-pitch", "learned"),
            ("rate gate", "rate", "step-x+step-time+ankle-pitch", "learned"),
            ("step-x,step-time alone", "../leaderboard-sets-default", "step-x+step-time", "learned"),
            ("model", "rate", "step-x+step-time+ankle-pitch", "model")]:
        sums = [0] * len(KEYS)
        for s in range(5):
            fc = summary(f"{where}/stability__{approx}__pendulum-cart__s{s}__{learn}")["fall_causes"][walker]
            sums = [a + fc[k] for a, k in zip(sums, KEYS)]
        print(f"| {approx} | {label} | " + " | ".join(map(str, sums)) + " |")
