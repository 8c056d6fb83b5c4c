"""The model's I50 with configs/landing.toml over the default's, by sector, paired by seed (this
bench against ../omnidirectional-learn-xyt-dz, the same command without the config).
Run: python3 model_vs_default.py (in this directory)."""
import glob, json, statistics as st

def load(d):
    runs = [json.load(open(f)) for f in sorted(glob.glob(d + "/omni*/summary.json"))]
    return {r["seed"]: r for r in runs}

a, b = load("../omnidirectional-learn-xyt-dz"), load(".")
for k, deg in enumerate(a[5]["sectors_deg"]):
    r = [b[s]["i50_ns"]["model"][k] / a[s]["i50_ns"]["model"][k] for s in a]
    print(f"{deg:5.0f} deg: landing / default {st.mean(r):.3f}")
r = [sum(b[s]["i50_ns"]["model"]) / sum(a[s]["i50_ns"]["model"]) for s in a]
print(f"sectors' mean: {st.mean(r):.3f} (per seed {', '.join(f'{x:.3f}' for x in r)})")
