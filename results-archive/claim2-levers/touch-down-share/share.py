#!/usr/bin/env python3
"""Claim 2's return between touch-downs recomputed from experiment B's stored steps and pushes
for each touch-down share (a touch-down counts when at least that share of the absorbed pushes
reach it within the 4 s horizon), learned - model per seed, mean [95% Student-t interval].

    python3 share.py            # seeds 0-4, the runs stored here
    python3 share.py DIR...     # other runs of `steplearn experiment disturbance --out DIR`
"""
import bisect, csv, gzip, math, os, statistics as st, sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(os.path.dirname(HERE)))
from paired import mean_h  # noqa: E402

HORIZON, TOLERANCE, F_R, INDICES = 4.0, 0.03, 0.20, 12


def rows(path):
    if os.path.exists(path):
        return list(csv.DictReader(open(path)))
    return list(csv.DictReader(gzip.open(path + ".gz", "rt")))


def by_index(steps, absorbed):
    """Per touch-down index after an absorbed push: its steps F_hat and their times since it."""
    steps_k, times_k = [[] for _ in range(INDICES)], [[] for _ in range(INDICES)]
    event, k = 0, 0
    for t, f_hat in steps:
        i = bisect.bisect_right(absorbed, t)
        if i == 0:
            continue
        if i != event:
            event, k = i, 0
        if t - absorbed[i - 1] < HORIZON and k < INDICES:
            steps_k[k].append(f_hat)
            times_k[k].append(t - absorbed[i - 1])
        k += 1
    return steps_k, times_k


def return_time(steps_k, times_k, min_count):
    points = [(st.mean(times_k[k]), abs(st.mean(steps_k[k]) - F_R))
              for k in range(INDICES) if len(steps_k[k]) >= max(1, min_count)]
    if not points:
        return HORIZON
    off = [i for i, (_, e) in enumerate(points) if e > TOLERANCE]
    if not off:
        return points[0][0]
    k = off[-1]
    if k + 1 == len(points):
        return HORIZON
    (t0, e0), (t1, e1) = points[k], points[k + 1]
    return min(HORIZON, t0 + (e0 - TOLERANCE) / (e0 - e1) * (t1 - t0))


def learned_minus_model(run, share):
    steps = {"model": [], "learned": []}
    for r in rows(os.path.join(run, "disturbance_steps.csv")):
        steps[r["controller"]].append((float(r["time_s"]), float(r["f_hat_m"])))
    absorbed = {"model": [], "learned": []}
    for r in rows(os.path.join(run, "disturbance_pushes.csv")):
        if r["fell"] == "false":
            absorbed[r["controller"]].append(float(r["time_s"]))
    t = {}
    for c in steps:
        steps_k, times_k = by_index(steps[c], absorbed[c])
        t[c] = return_time(steps_k, times_k, math.ceil(share * len(absorbed[c])))
    return t["learned"] - t["model"]


if __name__ == "__main__":
    runs = sys.argv[1:] or [os.path.join(HERE, f"s{s}") for s in range(5)]
    for share in (0.0, 0.1, 0.25, 0.5, 0.75, 0.9):
        d = [learned_minus_model(r, share) for r in runs]
        m, h = mean_h(d)
        print(f"share {share:4}: " + " ".join(f"{x:+.2f}" for x in d)
              + f"  mean {m:+.2f} [{m - h:+.2f}, {m + h:+.2f}]")
