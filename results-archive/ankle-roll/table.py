#!/usr/bin/env python3
"""The learned sole roll in C, paired by seed with step-x,step-y,step-time's runs on the same
pushes (the model is the same walker in both; checked).

python3 table.py TAG[:BASE]... prints per tag and seed group: sideways (per seed the summed
left and right I50s, learner over model), its base's (the lateral levers' `step-x,step-y,
step-time` runs with config BASE, default `default`) and the learner over the base learner;
pushed forward (if run) the same against ../leaderboard-sets-default (BASE `default`, seeds 0-4),
../judge-sets-landing (`default`, seeds 5-9) or the lateral levers' C-forward-BASE runs; then the fall causes summed.
"""
import os
import sys
from collections import Counter

HERE = os.path.dirname(os.path.abspath(__file__))
os.chdir(HERE)
sys.path.insert(0, os.path.dirname(HERE))
from paired import i50, interval, summary  # noqa: E402

GROUPS = [[0, 1, 2, 3, 4], [5, 6, 7, 8, 9]]


def base(config, direction, seed):
    if direction == "forward":
        if config == "default" and seed >= 5:
            return f"../judge-sets-landing/C-step-x,step-y,step-time-forward-s{seed}"
        if config == "default":
            return ("../leaderboard-sets-default/"
                    f"stability__lwpr__pendulum-cart__s{seed}__step-x+step-y+step-time")
        return f"../lateral-levers/C-forward-{config}-s{seed}"
    return f"../lateral-levers/C-step-x+step-y+step-time-{config}-{direction}-s{seed}"


def runs(tag, config, directions, seeds):
    """Per seed with every direction present: (tag's summaries, base's summaries)."""
    out = {}
    for s in seeds:
        paths = [(f"C-{tag}-{d}-s{s}", base(config, d, s)) for d in directions]
        if all(os.path.exists(os.path.join(p, "summary.json")) for pair in paths for p in pair):
            out[s] = ([summary(a) for a, _ in paths], [summary(b) for _, b in paths])
    return out


def main():
    for arg in sys.argv[1:]:
        tag, _, config = arg.partition(":")
        config = config or "default"
        for seeds in GROUPS:
            for name, dirs in [("sideways", ["left", "right"]), ("forward", ["forward"])]:
                r = runs(tag, config, dirs, seeds)
                if not r:
                    continue
                for mine, theirs in r.values():
                    for a, b in zip(mine, theirs):
                        assert i50(a, "model") == i50(b, "model"), "the model differs"
                tot = lambda ss, w: sum(i50(s, w) for s in ss)
                lm = [tot(a, "learned") / tot(a, "model") for a, _ in r.values()]
                bm = [tot(b, "learned") / tot(b, "model") for _, b in r.values()]
                lb = [tot(a, "learned") / tot(b, "learned") for a, b in r.values()]
                print(f"{tag} seeds {min(r)}-{max(r)} ({len(r)}), {name}: learned / model "
                      f"{interval(lm)}; step-x,step-y,step-time ({config}) {interval(bm)}; "
                      f"learned / that learner {interval(lb)}")
                for w in ["model", "learned"]:
                    c = Counter()
                    for a, _ in r.values():
                        for s in a:
                            c.update(s["fall_causes"][w])
                    print(f"    falls {w:7}: "
                          + ", ".join(f"{k} {v}" for k, v in sorted(c.items()) if v))
                c = Counter()
                for _, b in r.values():
                    for s in b:
                        c.update(s["fall_causes"]["learned"])
                print("    falls base   : " + ", ".join(f"{k} {v}" for k, v in sorted(c.items()) if v))


if __name__ == "__main__":
    main()
