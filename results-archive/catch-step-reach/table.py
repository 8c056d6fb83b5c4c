"""Means over seeds 5-9 of the catch step's reach and of learned / model I50 (paired by seed,
95% Student-t interval), per learned set and direction, from the summaries run.sh wrote."""
import glob, json, math, statistics as st

T975 = {4: 2.776}

def ci(v):
    m = st.mean(v)
    h = T975[len(v) - 1] * st.stdev(v) / math.sqrt(len(v))
    return m, m - h, m + h

print("| learned set | pushes | model I50 (Ns) | reach, model | reach, learned | learned / model I50 |")
print("|---|---|---|---|---|---|")
for learn in ["step-x", "step-x_step-time"]:
    for d in ["forward", "backward"]:
        rows = []
        for s in range(5, 10):
            p = f"C-{learn}-{d}-s{s}/summary.json"
            try:
                j = json.load(open(p))
            except FileNotFoundError:
                continue
            c = j["controllers"]
            r = j["catch_step_reach"]
            rows.append((c["model"]["impulse_at_50pct_fall_ns"],
                         c["learned"]["impulse_at_50pct_fall_ns"], r["model"], r["learned"]))
        if len(rows) < 5:
            print(f"| {learn} | {d} | ({len(rows)} of 5 seeds done) |")
            continue
        m, lo, hi = ci([l / mo for mo, l, _, _ in rows])
        print(f"| `{learn.replace('_', ',')}` | {d} | {st.mean(r[0] for r in rows):.2f} | "
              f"{st.mean(r[2] for r in rows):.2f} | {st.mean(r[3] for r in rows):.2f} | "
              f"{m:.3f} [{lo:.3f}, {hi:.3f}] |")
