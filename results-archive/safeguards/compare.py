#!/usr/bin/env python3
"""Experiment B on seeds 0-4 with the defaults (../paper) and with one safeguard off: anti-windup
(`no-aw/`, `anti_windup = false`) and the trust region (`no-trust/`, `trust_region = 1e6`, no
fade within reach). Per seed, learned - model: the return time between touch-downs and the
share of pushes that end in a fall; mean [95% interval] over the five seeds.

    python3 results-archive/safeguards/compare.py
"""
import glob, json, os, sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from paired import interval  # noqa: E402


def figures(job):
    ret, falls = [], []
    for seed in range(5):
        s = json.load(open(os.path.join(job, f"disturbance__lwpr__pendulum-cart__s{seed}", "summary.json")))
        f = s["falls"]
        share = lambda w: f["falls"][w] / f["pushes"][w]
        falls.append(share("learned") - share("model"))
        t = s["return_time_by_step_s"]
        ret.append(t["learned"] - t["model"])
    return ret, falls


for name, job in [("defaults", os.path.join(HERE, "..", "paper")), ("anti-windup off", os.path.join(HERE, "no-aw")), ("trust region off", os.path.join(HERE, "no-trust"))]:
    ret, falls = figures(job)
    print(f"{name}: return {interval(ret)} s; fall share {interval(falls)}")
