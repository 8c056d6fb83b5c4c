# Each combination's learned I50 with the default swing over the same combination's with steps on
# time (../leaderboard-sets, the default until 2026-11-28), paired by seed: mean and 95% interval.
#   python3 compare.py
import glob, json, math, os, statistics as st

HERE = os.path.dirname(os.path.abspath(__file__))

def i50(d, walker):
    return json.load(open(os.path.join(d, "summary.json")))["controllers"][walker][
        "impulse_at_50pct_fall_ns"]

def interval(v):
    m = st.mean(v); h = 2.776 * st.stdev(v) / math.sqrt(len(v))
    return f"{m:.3f} [{m - h:.3f}, {m + h:.3f}]"

print("| approx | learned set | learned / learned on time | model / model on time |")
print("|---|---|---|---|")
for approx in ["lwpr", "rbf", "grid", "kernel-ridge"]:
    for learn in ["step-x+step-time", "step-x+step-y+step-time"]:
        ratios, models = [], []
        for s in range(5):
            name = f"stability__{approx}__pendulum-cart__s{s}__{learn}"
            new, old = os.path.join(HERE, name), os.path.join(HERE, "..", "leaderboard-sets", name)
            ratios.append(i50(new, "learned") / i50(old, "learned"))
            models.append(i50(new, "model") / i50(old, "model"))
        print(f"| {approx} | {learn.replace('+', ',')} | {interval(ratios)} | {interval(models)} |")
