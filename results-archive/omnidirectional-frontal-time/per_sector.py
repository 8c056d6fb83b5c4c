"""Per-sector I50 of the walker `learned` (step-x,step-y,step-time) over the model, paired over a
bench's seeds (mean of the per-seed ratios, 95% Student-t interval), the sectors' mean (ratio of
the sectors' mean I50s, as the experiment defines it), the two lateral sectors' (90 and 270
degrees), and the same walker over REF's `learned` on the same seeds (the same model).
Run: python3 per_sector.py [DIR] [REF] (defaults: this directory, ../omnidirectional-default)."""
import glob, json, os, sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from paired import interval as ci  # noqa: E402


def load(d):
    return {r["seed"]: r for r in (json.load(open(f)) for f in glob.glob(os.path.join(d, "omni*/summary.json")))}


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else HERE
    ref = load(sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, "..", "omnidirectional-default"))
    runs = load(d)
    seeds = sorted(runs)
    sectors = runs[seeds[0]]["sectors_deg"]
    lateral = [sectors.index(90.0), sectors.index(270.0)]
    i50 = lambda r, w, k: r["i50_ns"][w][k]
    for name, other, w2 in [("model", runs, "model"), ("the reference's learned", ref, "learned")]:
        pair = [s for s in seeds if s in other]
        print(f"learned / {name}, seeds {pair}")
        for k, deg in enumerate(sectors):
            print(f"  {deg:5.0f} deg: {ci([i50(runs[s], 'learned', k) / i50(other[s], w2, k) for s in pair])}")
        print("  sectors' mean:", ci([sum(runs[s]["i50_ns"]["learned"]) / sum(other[s]["i50_ns"][w2]) for s in pair]))
        side = lambda r, w: sum(i50(r, w, k) for k in lateral)
        print("  lateral (90, 270):", ci([side(runs[s], "learned") / side(other[s], w2) for s in pair]))
    print("model / the reference's model:", ci([sum(runs[s]["i50_ns"]["model"]) / sum(ref[s]["i50_ns"]["model"]) for s in seeds if s in ref]))


if __name__ == "__main__":
    main()
