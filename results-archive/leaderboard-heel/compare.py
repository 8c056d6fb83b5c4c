#!/usr/bin/env python3
"""C, seeds 5-9: each approximator learning step-x,step-time with the sole's pitch on its heel
alone over the model, and over the same approximator learning step-x,step-time alone on the same
pushes, paired by seed. Pushed backward: this directory and without/; forward: forward/ and
forward/without/. LWPR's runs are ../ankle-pitch/C-h2-DIRECTION-s* and
../judge-sets-landing/C-step-x,step-time-DIRECTION-s*.
Run: python3 compare.py (from anywhere)."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
os.chdir(HERE)
sys.path.insert(0, os.path.dirname(HERE))
from paired import i50, interval, ratio, summary  # noqa: E402

SEEDS = range(5, 10)


def runs(approx, direction):
    if approx == "lwpr":
        return ([f"../ankle-pitch/C-h2-{direction}-s{s}" for s in SEEDS],
                [f"../judge-sets-landing/C-step-x,step-time-{direction}-s{s}" for s in SEEDS])
    here = "" if direction == "backward" else "forward/"
    return ([f"{here}stability__{approx}__pendulum-cart__s{s}__step-x+step-time+ankle-pitch" for s in SEEDS],
            [f"{here}without/stability__{approx}__pendulum-cart__s{s}__step-x+step-time" for s in SEEDS])


for direction, approx in [(d, a) for d in ["backward", "forward"]
                          for a in ["lwpr", "rbf", "grid", "kernel-ridge"]]:
    if approx == "lwpr":
        print(f"{direction}, seeds 5-9: learned / model with the heel | step-x,step-time alone | difference")
    heel, alone = runs(approx, direction)
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

# The heel gated by the fall (gated/, ninth session) beside the ungated heel on the same pushes.
for direction in ["backward", "forward"]:
    print(f"{direction}, seeds 5-9, the heel gated by the fall: learned / model | ungated heel | difference")
    for approx in ["rbf", "grid"]:
        gated = [f"gated/{direction}/stability__{approx}__pendulum-cart__s{s}__step-x+step-time+ankle-pitch"
                 for s in SEEDS]
        heel, _ = runs(approx, direction)
        if not all(os.path.exists(os.path.join(d, "summary.json")) for d in gated):
            print(f"{approx}: runs missing")
            continue
        a, b = [], []
        for g, h in zip(gated, heel):
            sg, sh = summary(g), summary(h)
            assert i50(sg, "model") == i50(sh, "model"), "the model differs"
            a.append(i50(sg, "learned") / i50(sg, "model"))
            b.append(i50(sh, "learned") / i50(sh, "model"))
        print(f"{approx}: {interval(a)} | {interval(b)} | {interval([x - y for x, y in zip(a, b)])}")

# step-x,step-time alone on five more seeds that chose nothing (10-14; seeds-10-14/ backward,
# seeds-10-14/forward/ forward, tenth session; LWPR's runs are ../ankle-pitch/C-xt-DIRECTION-s*),
# alone and pooled with 5-9.
for direction in ["backward", "forward"]:
    print(f"{direction}, step-x,step-time alone: learned / model, seeds 10-14 | seeds 5-14")
    for approx in ["lwpr", "rbf", "grid"]:
        here = "seeds-10-14" if direction == "backward" else "seeds-10-14/forward"
        if approx == "lwpr":
            later = [f"../ankle-pitch/C-xt-{direction}-s{s}" for s in range(10, 15)]
        else:
            later = [f"{here}/stability__{approx}__pendulum-cart__s{s}__step-x+step-time" for s in range(10, 15)]
        if not all(os.path.exists(os.path.join(d, "summary.json")) for d in later):
            print(f"{approx}: runs missing")
            continue
        _, earlier = runs(approx, direction)
        a = [ratio(summary(d)) for d in later]
        print(f"{approx}: {interval(a)} | {interval(a + [ratio(summary(d)) for d in earlier])}")
