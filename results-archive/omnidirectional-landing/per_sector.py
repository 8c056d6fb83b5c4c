"""Per-sector I50 of each learning walker over the model, paired over this bench's seeds (mean of
the per-seed ratios, 95% Student-t interval), the sectors' mean (ratio of the sectors' mean I50s,
as the experiment defines it) and the two lateral sectors' (90 and 270 degrees).
Run: python3 per_sector.py (in this directory)."""
import glob, json, os, sys

HERE = os.path.dirname(os.path.abspath(__file__))
os.chdir(HERE)
sys.path.insert(0, os.path.dirname(HERE))
from paired import interval as ci  # noqa: E402
runs = [json.load(open(f)) for f in sorted(glob.glob("omni*/summary.json"))]


sectors = runs[0]["sectors_deg"]
lateral = [sectors.index(90.0), sectors.index(270.0)]
for w in ["learned", "both", "sagittal"]:
    print(f"{w} / model, {len(runs)} seeds")
    for k, deg in enumerate(sectors):
        print(f"  {deg:5.0f} deg: {ci([r['i50_ns'][w][k] / r['i50_ns']['model'][k] for r in runs])}")
    print("  sectors' mean:", ci([sum(r["i50_ns"][w]) / sum(r["i50_ns"]["model"]) for r in runs]))
    side = lambda r, v: sum(r["i50_ns"][v][k] for k in lateral)
    print("  lateral (90, 270):", ci([side(r, w) / side(r, "model") for r in runs]))
