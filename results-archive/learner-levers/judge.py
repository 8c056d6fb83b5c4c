# The levers judged on seeds 5-9 (C, 400 pushes, --learn step-x,step-time): learned / model and
# learned / the default learner on the same seed (../judge-sets-landing, the same model), paired
# by seed, mean and 95% Student-t interval.
#   python3 judge.py
import json, math, os, statistics as st

HERE = os.path.dirname(os.path.abspath(__file__))
T = {2: 12.706, 3: 4.303, 4: 3.182, 5: 2.776}

def get(d):
    c = json.load(open(os.path.join(d, "summary.json")))["controllers"]
    return c["model"]["impulse_at_50pct_fall_ns"], c["learned"]["impulse_at_50pct_fall_ns"]

def interval(v):
    m = st.mean(v); h = T[len(v)] * st.stdev(v) / math.sqrt(len(v))
    return f"{m:.3f} [{m - h:.3f}, {m + h:.3f}]"

for lever in ["kernel-ridge", "maxoff0.05"]:
    for dirn in ["forward", "backward"]:
        lm, vs = [], []
        for s in range(5, 10):
            d = os.path.join(HERE, f"C-{lever}-{dirn}-s{s}")
            if not os.path.exists(os.path.join(d, "summary.json")):
                continue
            m, l = get(d)
            m0, l0 = get(os.path.join(HERE, "..", "judge-sets-landing", f"C-step-x,step-time-{dirn}-s{s}"))
            assert m == m0, f"{d}: not the judge runs' model"
            lm.append(l / m); vs.append(l / l0)
        if len(lm) >= 2:
            print(f"{lever:12} {dirn:8} seeds {len(lm)}: learned / model {interval(lm)}, "
                  f"learned / default learner {interval(vs)}")
