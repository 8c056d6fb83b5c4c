#!/usr/bin/env python3
"""The learned sole pitch in C, paired by seed with step-x,step-time's runs on the same pushes.

python3 table.py TAG...   (from this directory) prints, per tag, seed group and direction, the
mean and Student-t 95% interval of the learner's I50 over the model's in the same run (the model
is the default one: no setting here changes it), the same for `step-x,step-time` on the same
seeds, and their paired difference; then the fall causes summed over the group.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
os.chdir(HERE)
sys.path.insert(0, os.path.dirname(HERE))
from paired import i50, interval, ratio, summary  # noqa: E402


def base_run(seed, direction):
    if seed < 5:
        return f"../learner-levers/C-default-{direction}-s{seed}"
    if seed < 10:
        return f"../judge-sets-landing/C-step-x,step-time-{direction}-s{seed}"
    return f"C-xt-{direction}-s{seed}"  # step-x,step-time run here on seeds 10-14 (tag xt)


for tag in sys.argv[1:] or ["v1"]:
    for name, seeds in [("seeds 0-4", range(0, 5)), ("seeds 5-9", range(5, 10)),
                        ("seeds 10-14", range(10, 15))]:
        for direction in ["forward", "backward"]:
            done = [s for s in seeds if os.path.exists(f"C-{tag}-{direction}-s{s}/summary.json")]
            if not done:
                continue
            if not all(os.path.exists(base_run(s, direction)) for s in done):
                # No step-x,step-time run on these seeds: the learner over the model alone.
                ours = [ratio(summary(f"C-{tag}-{direction}-s{s}")) for s in done]
                print(f"{tag} {name} ({len(done)} seeds), {direction}: learned / model {interval(ours)}")
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
