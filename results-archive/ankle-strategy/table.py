#!/usr/bin/env python3
"""The ankle strategy in C, paired by seed with the defaults' runs on the same pushes.

python3 table.py   (from this directory) prints, per seed group and direction, the mean and
Student-t 95% interval of: the model's I50 with the ankle strategy over the default model's, the
learner's over the model's in the same run, and the learner with it over the default learner.
"""
import json
import math
import os

T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262}


def i50(path, walker):
    with open(os.path.join(path, "summary.json")) as f:
        return json.load(f)["controllers"][walker]["impulse_at_50pct_fall_ns"]


def reach(path):
    with open(os.path.join(path, "summary.json")) as f:
        return json.load(f)["catch_step_reach"]["model"]


def interval(xs):
    n = len(xs)
    m = sum(xs) / n
    if n < 2:
        return f"{m:.3f}"
    sd = math.sqrt(sum((x - m) ** 2 for x in xs) / (n - 1))
    h = T975[n - 1] * sd / math.sqrt(n)
    return f"{m:.3f} [{m - h:.3f}, {m + h:.3f}]"


def default_run(seed, direction):
    if seed < 5:
        return f"../learner-levers/C-default-{direction}-s{seed}"
    return f"../judge-sets-landing/C-step-x,step-time-{direction}-s{seed}"


for name, seeds in [("seeds 0-4", range(0, 5)), ("seeds 5-9", range(5, 10))]:
    for direction in ["forward", "backward"]:
        done = [s for s in seeds
                if os.path.exists(f"C-a1-{direction}-s{s}/summary.json")]
        if not done:
            continue
        model, learned, self_ratio, reaches, models = [], [], [], [], []
        for s in done:
            run, base = f"C-a1-{direction}-s{s}", default_run(s, direction)
            models.append(i50(run, "model"))
            model.append(i50(run, "model") / i50(base, "model"))
            learned.append(i50(run, "learned") / i50(run, "model"))
            self_ratio.append(i50(run, "learned") / i50(base, "learned"))
            reaches.append(reach(run))
        print(f"{name} ({len(done)} seeds), {direction}: model I50 {sum(models) / len(models):.2f} Ns, "
              f"model / default model {interval(model)}; learned / model {interval(learned)}; "
              f"learned / default learned {interval(self_ratio)}; model reach "
              f"{sum(reaches) / len(reaches):.3f}")
