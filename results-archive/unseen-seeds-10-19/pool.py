#!/usr/bin/env python3
"""Claims 1, 2 and 4 with the defaults on seeds 0-9 (the main job, results-archive/paper), on
seeds 10-19 (this bench) and pooled over 0-19: each claim's headline per seed computed from
the stored summaries as the main job computes it, mean [95% Student-t interval].

    python3 results-archive/unseen-seeds-10-19/pool.py
"""
import glob, json, os, sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from paired import interval  # noqa: E402


def per_seed(job, experiment, value):
    out = []
    for path in sorted(glob.glob(os.path.join(job, f"{experiment}__*", "summary.json"))):
        v = value(json.load(open(path)))
        if v is not None:
            out.append(v)
    return out


def tracking(s):
    std = s["step_error_std_m"]
    d = [100 * (l - m) for m, l in zip(std["model"], std["learned"]) if m is not None and l is not None]
    return sum(d) / len(d) if d else None


def disturbance(s):
    f = s["falls"]
    if f["pushes"]["model"] - f["falls"]["model"] <= 0 or f["pushes"]["learned"] - f["falls"]["learned"] <= 0:
        return None
    t = s["return_time_by_step_s"]
    return t["learned"] - t["model"]


def robustness(s):
    return sum(s["absorbed_by_push"]) - sum(s["no_learning"]["absorbed_by_push"])


paper = os.path.join(HERE, "..", "paper")
for name, f in [("tracking", tracking), ("disturbance", disturbance), ("robustness", robustness)]:
    a, b = per_seed(paper, name, f), per_seed(HERE, name, f)
    print(f"{name}: seeds 0-9 {interval(a)}; 10-19 {interval(b)}; 0-19 {interval(a + b)}")
