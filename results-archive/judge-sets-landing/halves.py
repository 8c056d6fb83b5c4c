# Learned / model I50 over the first and the second half of each run's pushes (the learner has
# learned from more pushes in the second half), paired by seed; logistic fit by Newton's method
# (the library's estimator fits the same model).
#   python3 halves.py [GLOB]   GLOB with {dirn} and {set}; default: this directory's runs
import csv, glob, math, os, statistics as st, sys

HERE = os.path.dirname(os.path.abspath(__file__))
PAT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "C-{set}-{dirn}-s*")

def loglik(rows, b0, b1):
    ll = 0.0
    for x, y in rows:
        z = b0 + b1 * x
        ll += y * z - (z + math.log1p(math.exp(-z)) if z > 0 else math.log1p(math.exp(z)))
    return ll

def i50(rows):
    xs = [x for x, _ in rows]
    b0, b1 = -0.5 * st.mean(xs), 0.5
    ll = loglik(rows, b0, b1)
    for _ in range(200):
        g0 = g1 = h00 = h01 = h11 = 0.0
        for x, y in rows:
            p = 1 / (1 + math.exp(-max(min(b0 + b1 * x, 35), -35)))
            w = p * (1 - p)
            g0 += y - p; g1 += (y - p) * x
            h00 += w; h01 += w * x; h11 += w * x * x
        det = h00 * h11 - h01 * h01
        if det <= 0: break
        d0 = (h11 * g0 - h01 * g1) / det; d1 = (h00 * g1 - h01 * g0) / det
        t = 1.0
        while t > 1e-6 and loglik(rows, b0 + t * d0, b1 + t * d1) < ll:
            t *= 0.5
        b0 += t * d0; b1 += t * d1; ll = loglik(rows, b0, b1)
        if abs(t * d0) + abs(t * d1) < 1e-10: break
    return -b0 / b1

def interval(v):
    m = st.mean(v); h = 2.776 * st.stdev(v) / math.sqrt(len(v)) if len(v) == 5 else float("nan")
    return f"{m:.3f} [{m - h:.3f}, {m + h:.3f}]"

for s in (["step-x,step-time", "step-x,step-y,step-time"] if "{set}" in PAT else ["runs"]):
    for dirn in (["forward", "backward"] if "{dirn}" in PAT else ["forward"]):
        first, second = [], []
        for d in sorted(glob.glob(PAT.format(dirn=dirn, set=s))):
            rows = {}
            for r in csv.DictReader(open(os.path.join(d, "pushes.csv"))):
                rows.setdefault(r["controller"], []).append(
                    (float(r["impulse_ns"]), 1.0 if r["fell"] == "true" else 0.0))
            m, l = rows["model"], rows["learned"]
            h = len(m) // 2
            first.append(i50(l[:h]) / i50(m[:h])); second.append(i50(l[h:]) / i50(m[h:]))
        if first:
            diff = [b - a for a, b in zip(first, second)]
            print(f"{s:24} {dirn:8} seeds {len(first)}: first half {interval(first)}, "
                  f"second half {interval(second)}, second - first {interval(diff)}")
