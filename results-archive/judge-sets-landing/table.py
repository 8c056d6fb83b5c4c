# Experiment C on seeds 5-9 with the default swing (run.sh): per learned set and direction, the
# model's I50 and catch step reach, and the learned walker's I50 over the model's on the same
# pushes, paired by seed (mean and 95% Student-t interval).
import json, os, statistics as st, sys
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from paired import i50, mean_h, summary  # noqa: E402
NAMES = ["step-x,step-time", "step-x,step-y,step-time"]
SETS = [(name, os.path.join(HERE, "C-" + name + "-{d}-s{s}")) for name in NAMES]
# The defaults until 2026-11-28 (steps on time), on the same seeds and pushes.
BEFORE = {name: os.path.join(HERE, "..", "judge-sets", "C-" + name + "-{d}-s{s}") for name in NAMES}

def ci(xs):
    m, h = mean_h(xs)  # h is nan for one value
    return f"{m:.3f} [{m - h:.3f}, {m + h:.3f}]"

def runs(pattern, d):
    out = {}
    for s in range(5, 10):
        run = pattern.format(d=d, s=s)
        if os.path.exists(run + "/summary.json"):
            j = summary(run)
            r = j["catch_step_reach"]
            out[s] = (i50(j, "model"), i50(j, "learned"), r["model"], r["learned"])
    return out

print("| learned set | pushes | seeds | model I50 (Ns) | reach, model | reach, learned | learned / model I50 "
      "| model / model on time | learned / learned on time | learned / model on time |")
print("|---|---|---|---|---|---|---|---|---|---|")
for name, pattern in SETS:
    for d in ["forward", "backward"]:
        now, before = runs(pattern, d), runs(BEFORE[name], d)
        if not now:
            continue
        rows = list(now.values())
        paired = [(now[s], before[s]) for s in now if s in before]
        print(f"| `{name}` | {d} | {len(rows)} | {st.mean(m for m, _, _, _ in rows):.2f} | "
              f"{st.mean(a for _, _, a, _ in rows):.3f} | {st.mean(b for _, _, _, b in rows):.3f} | "
              f"{ci([l / m for m, l, _, _ in rows])} | {ci([n[0] / b[0] for n, b in paired])} | "
              f"{ci([n[1] / b[1] for n, b in paired])} | {ci([n[1] / b[0] for n, b in paired])} |")

# Fall causes (summed over the seeds), per walker, with the default and with steps on time.
print()
print("| learned set | pushes | swing | walker | falls | tipped after the catch step | catch step clamped | later step clamped | before touch-down | other |")
print("|---|---|---|---|---|---|---|---|---|---|")
for name, pattern in SETS:
    for d in ["forward", "backward"]:
        for label, pat in [("default", pattern), ("on time", BEFORE[name])]:
            tot = {"model": {}, "learned": {}}
            for s in range(5, 10):
                f = pat.format(d=d, s=s) + "/summary.json"
                if not os.path.exists(f):
                    continue
                causes = json.load(open(f))["fall_causes"]
                for w in tot:
                    for k, v in causes[w].items():
                        tot[w][k] = tot[w].get(k, 0) + v
            for w, c in tot.items():
                if not c:
                    continue
                main = ["tipped_after_catch_step", "catch_step_clamped", "later_step_clamped", "before_touch_down"]
                print(f"| `{name}` | {d} | {label} | {w} | {sum(c.values())} | "
                      + " | ".join(str(c.get(k, 0)) for k in main)
                      + f" | {sum(v for k, v in c.items() if k not in main)} |")
