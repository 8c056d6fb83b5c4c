#!/usr/bin/env python3
"""The ankle strategy in C, paired by seed with the defaults' runs on the same pushes.

python3 table.py   (from this directory) prints, per seed group and direction, the mean and
Student-t 95% interval of: the model's I50 with the ankle strategy over the default model's, the
learner's over the model's in the same run, and the learner with it over the default learner.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
os.chdir(HERE)
sys.path.insert(0, os.path.dirname(HERE))
from paired import i50, interval, summary  # noqa: E402


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
            run, base = summary(f"C-a1-{direction}-s{s}"), summary(default_run(s, direction))
            models.append(i50(run, "model"))
            model.append(i50(run, "model") / i50(base, "model"))
            learned.append(i50(run, "learned") / i50(run, "model"))
            self_ratio.append(i50(run, "learned") / i50(base, "learned"))
            reaches.append(run["catch_step_reach"]["model"])
        print(f"{name} ({len(done)} seeds), {direction}: model I50 {sum(models) / len(models):.2f} Ns, "
              f"model / default model {interval(model)}; learned / model {interval(learned)}; "
              f"learned / default learned {interval(self_ratio)}; model reach "
              f"{sum(reaches) / len(reaches):.3f}")
