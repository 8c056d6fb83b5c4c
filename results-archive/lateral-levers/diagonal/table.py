# Per azimuth (C, 200 pushes, the runs of run.sh): the walker learning step-x,step-y,step-time
# over the model (I50 ratio per seed; mean and 95% Student-t interval over the seeds present,
# levers.py's interval) and the model's mean I50.   python3 table.py [NAME]   (default both-dz0)
import glob, json, os, re, statistics as st, sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from levers import interval

name = sys.argv[1] if len(sys.argv) > 1 else "both-dz0"
runs = {}
for d in glob.glob(os.path.join(HERE, f"C-{name}-az*-s*")):
    m = re.search(r"-az(-?[\d.]+)-s(\d+)$", d)
    f = os.path.join(d, "summary.json")
    if m and os.path.exists(f):
        c = json.load(open(f))["controllers"]
        runs.setdefault(float(m[1]), []).append(
            (c["model"]["impulse_at_50pct_fall_ns"], c["learned"]["impulse_at_50pct_fall_ns"]))
for az in sorted(runs):
    r = [l / m for m, l in runs[az]]
    print(f"{name} azimuth {az:5.0f} deg, seeds {len(r)}: learned / model {interval(r)}, "
          f"model {st.mean(m for m, _ in runs[az]):.2f} Ns")
