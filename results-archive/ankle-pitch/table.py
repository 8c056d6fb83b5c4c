#!/usr/bin/env python3
"""The learned sole pitch in C, paired by seed with step-x,step-time's runs on the same pushes.

python3 table.py TAG...   (from this directory) prints, per tag, seed group and direction, the
mean and Student-t 95% interval of the learner's I50 over the model's in the same run (the model
is the default one: no setting here changes it), the same for `step-x,step-time` on the same
seeds, and their paired difference; then the fall causes summed over the group.
"""
import json
import math
import os
import sys

T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262}


def summary(path):
    with open(os.path.join(path, "summary.json")) as f:
        return json.load(f)


def ratio(s):
    c = s["controllers"]
    return c["learned"]["impulse_at_50pct_fall_ns"] / c["model"]["impulse_at_50pct_fall_ns"]


def interval(xs):
    n = len(xs)
    m = sum(xs) / n
    if n < 2:
        return f"{m:.3f}"
    sd = math.sqrt(sum((x - m) ** 2 for x in xs) / (n - 1))
    h = T975[n - 1] * sd / math.sqrt(n)
    return f"{m:.3f} [{m - h:.3f}, {m + h:.3f}]"


def base_run(seed, direction):
    if seed < 5:
        return f"../learner-levers/C-default-{direction}-s{seed}"
    return f"../judge-sets-landing/C-step-x,step-time-{direction}-s{seed}"


for tag in sys.argv[1:] or ["v1"]:
    for name, seeds in [("seeds 0-4", range(0, 5)), ("seeds 5-9", range(5, 10))]:
        for direction in ["forward", "backward"]:
            done = [s for s in seeds if os.path.exists(f"C-{tag}-{direction}-s{s}/summary.json")]
            if not done:
                continue
            ours, base, diff, causes, base_causes = [], [], [], {}, {}
            for s in done:
                run, b = summary(f"C-{tag}-{direction}-s{s}"), summary(base_run(s, direction))
                ours.append(ratio(run))
                base.append(ratio(b))
                diff.append(ratio(run) - ratio(b))
                for k, v in run["fall_causes"]["learned"].items():
                    causes[k] = causes.get(k, 0) + v
                for k, v in b["fall_causes"]["learned"].items():
                    base_causes[k] = base_causes.get(k, 0) + v
            print(f"{tag} {name} ({len(done)} seeds), {direction}: learned / model {interval(ours)}; "
                  f"step-x,step-time {interval(base)}; difference {interval(diff)}")
            print("    falls of the learner by cause (this set / step-x,step-time): "
                  + ", ".join(f"{k} {causes[k]}/{base_causes.get(k, 0)}" for k in sorted(causes)))
