# The walker learning step-x,step-y,step-time pushed forward (C, 400 pushes, seeds 0-4): its I50
# over the model's with the step time learned sideways or in both planes (C-forward-NAME-s*,
# forward.sh) and sagittally (../leaderboard-sets-default, the same seeds and protocol), and each
# such learner over the default one, paired by seed (mean and 95% Student-t interval).
#   python3 forward.py
import glob, json, os, re, statistics as st

from levers import HERE, interval

def i50(d):
    c = json.load(open(os.path.join(d, "summary.json")))["controllers"]
    return c["model"]["impulse_at_50pct_fall_ns"], c["learned"]["impulse_at_50pct_fall_ns"]

def default(s):
    return os.path.join(HERE, "..", "leaderboard-sets-default",
                        f"stability__lwpr__pendulum-cart__s{s}__step-x+step-y+step-time")

names = sorted({re.match(r"C-forward-(.+)-s\d+$", os.path.basename(d))[1]
                for d in glob.glob(os.path.join(HERE, "C-forward-*-s*"))})
for name in names:
    rows = []
    for s in range(5):
        f = os.path.join(HERE, f"C-forward-{name}-s{s}")
        if os.path.exists(os.path.join(f, "summary.json")):
            rows.append((i50(f), i50(default(s))))
    assert all(abs(a[0] - b[0]) < 1e-12 for a, b in rows), "the model differs between the runs"
    print(f"{name}: seeds {len(rows)}, model {st.mean(a[0] for a, _ in rows):.2f} Ns")
    print(f"  {name} step time: learned / model", interval([a[1] / a[0] for a, _ in rows]))
    print("  sagittal step time: learned / model", interval([b[1] / b[0] for _, b in rows]))
    print(f"  {name} / sagittal learner", interval([a[1] / b[1] for a, b in rows]))
