# Per azimuth (C, 200 pushes, the runs of run.sh): the walker learning step-x,step-y,step-time
# over the model (I50 ratio per seed; mean and 95% Student-t interval over the seeds present)
# and the model's mean I50.   python3 table.py [NAME]   (default both-dz0)
import glob, json, math, os, re, statistics as st, sys

HERE = os.path.dirname(os.path.abspath(__file__))
T = {2: 12.706, 3: 4.303, 4: 3.182, 5: 2.776}
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
    mean = st.mean(r)
    ci = "" if len(r) < 2 else " [%.3f, %.3f]" % (mean - T[len(r)] * st.stdev(r) / math.sqrt(len(r)),
                                                 mean + T[len(r)] * st.stdev(r) / math.sqrt(len(r)))
    print(f"{name} azimuth {az:5.0f} deg, seeds {len(r)}: learned / model {mean:.3f}{ci}, "
          f"model {st.mean(m for m, _ in runs[az]):.2f} Ns")
