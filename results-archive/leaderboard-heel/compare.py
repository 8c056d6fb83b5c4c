#!/usr/bin/env python3
"""C pushed backward, seeds 5-9: each approximator learning step-x,step-time with the sole's pitch
on its heel alone (this directory) over the model, and over the same approximator learning
step-x,step-time alone on the same pushes (without/), paired by seed. LWPR's runs are
../ankle-pitch/C-h2-backward-s* and ../judge-sets-landing/C-step-x,step-time-backward-s*.
Run: python3 compare.py (from anywhere)."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
os.chdir(HERE)
sys.path.insert(0, os.path.dirname(HERE))
from paired import i50, interval, summary  # noqa: E402

SEEDS = range(5, 10)


def runs(approx):
    if approx == "lwpr":
        return ([f"../ankle-pitch/C-h2-backward-s{s}" for s in SEEDS],
                [f"../judge-sets-landing/C-step-x,step-time-backward-s{s}" for s in SEEDS])
    return ([f"stability__{approx}__pendulum-cart__s{s}__step-x+step-time+ankle-pitch" for s in SEEDS],
            [f"without/stability__{approx}__pendulum-cart__s{s}__step-x+step-time" for s in SEEDS])


print("backward, seeds 5-9: learned / model with the heel | step-x,step-time alone | difference")
for approx in ["lwpr", "rbf", "grid", "kernel-ridge"]:
    heel, alone = runs(approx)
    if not all(os.path.exists(os.path.join(d, "summary.json")) for d in heel + alone):
        print(f"{approx}: runs missing")
        continue
    a, b = [], []
    for h, w in zip(heel, alone):
        sh, sw = summary(h), summary(w)
        assert i50(sh, "model") == i50(sw, "model"), "the model differs"
        a.append(i50(sh, "learned") / i50(sh, "model"))
        b.append(i50(sw, "learned") / i50(sw, "model"))
    print(f"{approx}: {interval(a)} | {interval(b)} | {interval([x - y for x, y in zip(a, b)])}")
