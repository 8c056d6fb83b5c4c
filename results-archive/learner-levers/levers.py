# Per lever and direction (seeds 0-4, C with 400 pushes, --learn step-x,step-time): the learner's
# I50 over the model's (L/M) and over the default learner's on the same seed, mean and 95%
# Student-t interval, and the learner's catch step reach. The model is the same in every lever.
#   python3 levers.py [LEVER ...] (default: every lever run here; the first is the reference)
# judge.py judges levers on seeds 5-9 with the same helpers.
import os, statistics as st, sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from paired import i50, interval, summary  # noqa: E402  (judge.py imports interval from here)

def get(d):
    f = summary(d)
    return i50(f, "model"), i50(f, "learned"), f["catch_step_reach"]["learned"]

def main():
    levers = sys.argv[1:] or ["default", "nofalls", "leak0.02", "maxoff0.05", "share0.5"]
    for dirn in ["forward", "backward"]:
        ref = {}
        for lever in levers:
            rows = {}
            for s in range(5):
                d = os.path.join(HERE, f"C-{lever}-{dirn}-s{s}")
                if os.path.exists(os.path.join(d, "summary.json")):
                    rows[s] = get(d)
            if not rows:
                continue
            if lever == levers[0]:
                ref = rows
            lm = [l / m for m, l, _ in rows.values()]
            vs = [rows[s][1] / ref[s][1] for s in rows if s in ref]
            print(f"{dirn:8} {lever:11} seeds {len(rows)}: L/M {interval(lm)}, learned / {levers[0]} "
                  f"learned {interval(vs)}, learned reach {st.mean(r for _, _, r in rows.values()):.3f}")

if __name__ == "__main__":
    main()
