"""One line per file and walker: python3 table.py FILE.csv ... Columns: counted pushes; reach
(the library's mean of realised / last-tick command); early: counted catch steps whose swing
foot the generator released before the estimator's touch-down (lead < duration / 2), and among
them 'flipped': the last-tick command (already the next step's) against the push; their share
of the reach; short: counted catch steps touching down < 0.2 s after the step under way, their
share; reach_rel: mean realised / command at release (released command >= 0.1 m beyond F_R);
median of the same; mean learned dT and dF at the catch step."""
import csv, math, sys, statistics as st

def f(r, k):
    try:
        return float(r[k])
    except ValueError:
        return float('nan')

def early(r):
    lead = f(r, 'catch_lead')
    return not math.isnan(lead) and lead < 0.5 * f(r, 'catch_duration')

print("file walker counted reach early flipped flipped_share short short_share reach_rel median_rel dT dF")
for path in sys.argv[1:]:
    sgn = -1.0 if 'backward' in path else 1.0
    rows = list(csv.DictReader(open(path)))
    for w in ['model', 'learned']:
        C = [r for r in rows if r['walker'] == w and r['counted'] == 'true']
        n = len(C)
        E = [r for r in C if early(r)]
        F = [r for r in E if f(r, 'catch_commanded') * sgn < 0]
        S = [r for r in C if not early(r) and f(r, 'catch_duration') < 0.2]
        rel = [f(r, 'catch_realised') / f(r, 'catch_released') for r in C
               if abs(f(r, 'catch_released') - f(r, 'catch_f_r')) >= 0.1]
        print(f"{path} {w} {n} {sum(f(r,'ratio') for r in C)/n:.3f} {len(E)} {len(F)} "
              f"{sum(f(r,'ratio') for r in F)/n:+.3f} {len(S)} {sum(f(r,'ratio') for r in S)/n:+.3f} "
              f"{sum(rel)/len(rel):.3f} {st.median(rel):.3f} "
              f"{sum(f(r,'catch_dt') for r in C)/n:+.3f} {sum(f(r,'catch_df') for r in C)/n:+.3f}")
