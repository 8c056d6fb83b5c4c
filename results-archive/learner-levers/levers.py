# Per lever and direction (seeds 0-4, C with 400 pushes, --learn step-x,step-time): the learner's
# I50 over the model's (L/M) and over the default learner's on the same seed, mean and 95%
# Student-t interval, and the learner's catch step reach. The model is the same in every lever.
#   python3 levers.py [LEVER ...] (default: every lever run here; the first is the reference)
#   SEEDS=5,6,7,8,9 python3 levers.py maxoff0.05   (a lever judged on other seeds, alone)
import json, math, os, statistics as st, sys

HERE = os.path.dirname(os.path.abspath(__file__))
SEEDS = [int(x) for x in os.environ.get("SEEDS", "0,1,2,3,4").split(",")]
T = {2: 12.706, 3: 4.303, 4: 3.182, 5: 2.776}

def get(d):
    f = json.load(open(os.path.join(d, "summary.json")))
    c = f["controllers"]
    return (c["model"]["impulse_at_50pct_fall_ns"], c["learned"]["impulse_at_50pct_fall_ns"],
            f["catch_step_reach"]["learned"])

def interval(v):
    m = st.mean(v)
    if len(v) < 2:
        return f"{m:.3f}"
    h = T.get(len(v), 2.0) * st.stdev(v) / math.sqrt(len(v))
    return f"{m:.3f} [{m - h:.3f}, {m + h:.3f}]"

levers = sys.argv[1:] or ["default", "nofalls", "leak0.02", "maxoff0.05", "share0.5"]
for dirn in ["forward", "backward"]:
    ref = {}
    for lever in levers:
        rows = {}
        for s in SEEDS:
            d = os.path.join(HERE, f"C-{lever}-{dirn}-s{s}")
            if os.path.exists(os.path.join(d, "summary.json")):
                rows[s] = get(d)
        if not rows:
            continue
        if lever == levers[0]:
            ref = rows
        lm = [l / m for m, l, _ in rows.values()]
        vs = [rows[s][1] / ref[s][1] for s in rows if s in ref] or [float("nan")]
        print(f"{dirn:8} {lever:11} seeds {len(rows)}: L/M {interval(lm)}, learned / {levers[0]} "
              f"learned {interval(vs)}, learned reach {st.mean(r for _, _, r in rows.values()):.3f}")
