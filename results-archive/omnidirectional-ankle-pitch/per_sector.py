"""Per-sector I50 of the walker learning step-x,step-y,step-time,ankle-pitch over the model,
paired over seeds 5-9 (mean of the per-seed ratios, 95% Student-t interval), the sectors' mean
(ratio of the sectors' mean I50s, as the experiment defines it) and the two lateral sectors'
(90 and 270 degrees); beside it the same for step-x,step-y,step-time on the same pushes
(../omnidirectional-default/, the same model bit for bit) and the paired difference.
Run: python3 per_sector.py (in this directory)."""
import glob, json, os, sys

HERE = os.path.dirname(os.path.abspath(__file__))
os.chdir(HERE)
sys.path.insert(0, os.path.dirname(HERE))
from paired import interval as ci  # noqa: E402
ours = [json.load(open(f)) for f in sorted(glob.glob("omni*/summary.json"))]
base = [json.load(open(f)) for f in sorted(glob.glob("../omnidirectional-default/omni*/summary.json"))]
assert [r["seed"] for r in ours] == [r["seed"] for r in base]
for a, b in zip(ours, base):
    assert a["i50_ns"]["model"] == b["i50_ns"]["model"], "the model differs"


def rows(f):
    sectors = ours[0]["sectors_deg"]
    lateral = [sectors.index(90.0), sectors.index(270.0)]
    out = [(f"{deg:5.0f} deg", lambda r, k=k: r["i50_ns"]["learned"][k] / r["i50_ns"]["model"][k])
           for k, deg in enumerate(sectors)]
    out.append(("sectors' mean", lambda r: sum(r["i50_ns"]["learned"]) / sum(r["i50_ns"]["model"])))
    side = lambda r, v: sum(r["i50_ns"][v][k] for k in lateral)
    out.append(("lateral (90, 270)", lambda r: side(r, "learned") / side(r, "model")))
    return out


print(f"learned / model, {len(ours)} seeds: with ankle-pitch | step-x,step-y,step-time | difference")
for name, f in rows(None):
    a = [f(r) for r in ours]
    b = [f(r) for r in base]
    print(f"  {name}: {ci(a)} | {ci(b)} | {ci([x - y for x, y in zip(a, b)])}")
