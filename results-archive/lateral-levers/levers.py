# Per lever (learned set and config) on C pushed left and right: the learner's I50 over the
# model's, per direction and sideways (per seed the ratio of the summed left and right I50s),
# mean and 95% Student-t interval over the seeds present, the model's I50 and both walkers'
# falls by cause (summed), and the learner's sideways I50 over that of the same set's default
# learner (SET-default) on the same seeds. The model is the same walker in every lever.
#   python3 levers.py [SEEDS] (default "0 1 2 3 4"; "5 6 7 8 9" for the judge runs)
import glob, os, re, statistics as st, sys
from collections import Counter, defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from paired import interval, summary  # noqa: E402  (forward.py, diagonal/table.py import interval from here)

def main():
    seeds = [int(s) for s in (sys.argv[1] if len(sys.argv) > 1 else "0 1 2 3 4").split()]
    configs = [f[:-5] for f in os.listdir(HERE) if f.endswith(".toml")]
    runs = defaultdict(dict)
    for d in sorted(glob.glob(os.path.join(HERE, "C-*-s*"))):
        m = re.match(r"C-(.+)-(left|right)-s(\d+)$", os.path.basename(d))
        if not m or int(m[3]) not in seeds or not os.path.exists(os.path.join(d, "summary.json")):
            continue
        runs[m[1]][(m[2], int(m[3]))] = summary(d)
    for lever, r in runs.items():
        i50 = lambda k, w: r[k]["controllers"][w]["impulse_at_50pct_fall_ns"]
        parts = []
        for dirn in ["left", "right"]:
            keys = [k for k in r if k[0] == dirn]
            if keys:
                lm = [i50(k, "learned") / i50(k, "model") for k in keys]
                mod = st.mean(i50(k, "model") for k in keys)
                parts.append(f"{dirn} L/M {interval(lm)} (model {mod:.2f} Ns)")
        both = [s for s in seeds if ("left", s) in r and ("right", s) in r]
        side = [(i50(("left", s), "learned") + i50(("right", s), "learned"))
                / (i50(("left", s), "model") + i50(("right", s), "model")) for s in both]
        cfg = max((c for c in configs if lever.endswith("-" + c)), key=len)
        ref = runs.get(lever[: -len(cfg)] + "default", {})
        vs = [(i50(("left", s), "learned") + i50(("right", s), "learned"))
              / (ref[("left", s)]["controllers"]["learned"]["impulse_at_50pct_fall_ns"]
                 + ref[("right", s)]["controllers"]["learned"]["impulse_at_50pct_fall_ns"])
              for s in both if ("left", s) in ref and ("right", s) in ref]
        print(f"{lever}: seeds {len(both)}, sideways L/M {interval(side) if side else '-'}"
              + (f", learned / default learned {interval(vs)}" if vs else "") + "; "
              + "; ".join(parts))
        for w in ["model", "learned"]:
            c = Counter()
            for f in r.values():
                c.update(f["fall_causes"][w])
            print(f"    falls {w:7}: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items()) if v))

if __name__ == "__main__":
    main()
