"""Summaries of catch_anatomy's per-push CSVs: python3 analyse.py FILE.csv ...
(a file name containing 'backward' means backward pushes)."""
import csv, sys, statistics as st

def f(r, k):
    try:
        return float(r[k])
    except ValueError:
        return float('nan')

def mean(xs):
    xs = list(xs)
    return sum(xs) / len(xs) if xs else float('nan')

for path in sys.argv[1:]:
    sgn = -1.0 if 'backward' in path else 1.0
    rows = list(csv.DictReader(open(path)))
    print(f"== {path}")
    for w in ['model', 'learned']:
        R = [r for r in rows if r['walker'] == w]
        C = [r for r in R if r['counted'] == 'true']
        ratios = [f(r, 'ratio') for r in C]
        along = [r for r in C if f(r, 'catch_commanded') * sgn > 0]
        against = [r for r in C if f(r, 'catch_commanded') * sgn < 0]
        print(f"{w}: pushes {len(R)}, counted {len(C)}, reach (mean ratio) {mean(ratios):+.3f}, "
              f"median {st.median(ratios):+.3f}, sum realised / sum commanded "
              f"{sum(f(r,'catch_realised') for r in C) / sum(f(r,'catch_commanded') for r in C):+.3f}")
        for lab, S in [('commanded along the push', along), ('commanded against the push', against)]:
            if not S:
                print(f"  {lab}: 0")
                continue
            m = lambda k: mean(f(r, k) for r in S)
            print(f"  {lab}: {len(S)} ({len(S)/len(C):.0%}), mean ratio {m('ratio'):+.3f}, "
                  f"share of reach {sum(f(r,'ratio') for r in S)/len(C):+.3f}; "
                  f"ratio<0 in {sum(1 for r in S if f(r,'ratio')<0)}")
            print(f"    catch: first cmd {m('catch_first_commanded'):+.3f}, last cmd {m('catch_commanded'):+.3f} "
                  f"(analytic {m('catch_analytic'):+.3f}, dF {m('catch_df'):+.3f}), realised {m('catch_realised'):+.3f}, "
                  f"dT {m('catch_dt'):+.3f}, planned T {m('catch_planned_t'):.3f}, duration {m('catch_duration'):.3f}")
            print(f"    under way: cmd {m('under_commanded'):+.3f}, realised {m('under_realised'):+.3f}, "
                  f"dT {m('under_dt'):+.3f}, lands {mean(f(r,'under_time')-f(r,'time') for r in S):.3f} s after the push; "
                  f"after: cmd {m('after_commanded'):+.3f}, realised {m('after_realised'):+.3f}; impulse {m('impulse'):.2f}")
        if along:
            print(f"  reach over the along-the-push catch steps only: {mean(f(r,'ratio') for r in along):+.3f}")
