"""Per-sector I50 of each learning walker over the model, paired over this bench's seeds (mean of
the per-seed ratios, 95% Student-t interval), the sectors' mean (ratio of the sectors' mean I50s,
as the experiment defines it) and the two lateral sectors' (90 and 270 degrees).
Run: python3 per_sector.py (in this directory)."""
import glob, json, math

T95 = {2: 12.706, 3: 4.303, 4: 3.182, 5: 2.776, 6: 2.571, 7: 2.447, 8: 2.365, 9: 2.306, 10: 2.262}
runs = [json.load(open(f)) for f in sorted(glob.glob("omni*/summary.json"))]


def ci(xs):
    n = len(xs)
    m = sum(xs) / n
    h = T95[n] * math.sqrt(sum((x - m) ** 2 for x in xs) / (n - 1)) / math.sqrt(n)
    return f"{m:.3f} [{m - h:.3f}, {m + h:.3f}]"


sectors = runs[0]["sectors_deg"]
lateral = [sectors.index(90.0), sectors.index(270.0)]
for w in ["learned", "both", "sagittal"]:
    print(f"{w} / model, {len(runs)} seeds")
    for k, deg in enumerate(sectors):
        print(f"  {deg:5.0f} deg: {ci([r['i50_ns'][w][k] / r['i50_ns']['model'][k] for r in runs])}")
    print("  sectors' mean:", ci([sum(r["i50_ns"][w]) / sum(r["i50_ns"]["model"]) for r in runs]))
    side = lambda r, v: sum(r["i50_ns"][v][k] for k in lateral)
    print("  lateral (90, 270):", ci([side(r, w) / side(r, "model") for r in runs]))
