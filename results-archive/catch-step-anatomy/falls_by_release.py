"""Fall share of the pushes by impulse bin, split by whether the step under way at the push had
an early release (the generator exchanged its legs before the estimator's touch-down):
python3 falls_by_release.py FILE.csv ..."""
import csv, math, sys

def f(r, k):
    try:
        return float(r[k])
    except ValueError:
        return float('nan')

for path in sys.argv[1:]:
    rows = list(csv.DictReader(open(path)))
    print(f"== {path}")
    for w in ['model', 'learned']:
        R = [r for r in rows if r['walker'] == w and r['under_time']]
        out = []
        for lo, hi in [(0, 10), (10, 14), (14, 17), (17, 20)]:
            B = [r for r in R if lo <= f(r, 'impulse') < hi]
            e = [r for r in B if not math.isnan(f(r, 'under_lead')) and f(r, 'under_lead') < 0.5 * f(r, 'under_duration')]
            n = [r for r in B if r not in e]
            fr = lambda S: f"{sum(r['fell']=='true' for r in S)}/{len(S)}"
            out.append(f"[{lo},{hi}) Ns: early {fr(e)}, not {fr(n)}")
        print(f"{w}: " + "; ".join(out))
