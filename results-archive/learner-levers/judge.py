# The levers judged on seeds 5-9 (C, 400 pushes, --learn step-x,step-time): learned / model and
# learned / the default learner on the same seed (../judge-sets-landing, the same model), paired
# by seed, mean and 95% Student-t interval.
#   python3 judge.py
import os

from levers import HERE, get, interval

for lever in ["kernel-ridge", "maxoff0.05"]:
    for dirn in ["forward", "backward"]:
        lm, vs = [], []
        for s in range(5, 10):
            d = os.path.join(HERE, f"C-{lever}-{dirn}-s{s}")
            if not os.path.exists(os.path.join(d, "summary.json")):
                continue
            m, l, _ = get(d)
            m0, l0, _ = get(os.path.join(HERE, "..", "judge-sets-landing", f"C-step-x,step-time-{dirn}-s{s}"))
            assert m == m0, f"{d}: not the judge runs' model"
            lm.append(l / m); vs.append(l / l0)
        if len(lm) >= 2:
            print(f"{lever:12} {dirn:8} seeds {len(lm)}: learned / model {interval(lm)}, "
                  f"learned / default learner {interval(vs)}")
