"""Summaries of catch_anatomy's per-push CSVs: python3 analyse.py FILE.csv ...
(a file name containing 'backward' means backward pushes). 'Early release': the motion
generator exchanged its legs (the controller's support changed) before the estimator's
touch-down, within the second half of the step (lead < duration / 2)."""
import csv, math, sys, statistics as st


def f(r, k):
    try:
        return float(r[k])
    except ValueError:
        return float('nan')


def mean(xs):
    xs = [x for x in xs if not math.isnan(x)]
    return sum(xs) / len(xs) if xs else float('nan')


def early(r, s='catch'):
    lead = f(r, s + '_lead')
    return not math.isnan(lead) and lead < 0.5 * f(r, s + '_duration')


for path in sys.argv[1:]:
    sgn = -1.0 if 'backward' in path else 1.0
    rows = list(csv.DictReader(open(path)))
    print(f"== {path}")
    for w in ['model', 'learned']:
        R = [r for r in rows if r['walker'] == w]
        C = [r for r in R if r['counted'] == 'true']
        ratios = [f(r, 'ratio') for r in C]
        print(f"{w}: pushes {len(R)}, falls {sum(r['fell']=='true' for r in R)}, counted {len(C)}, "
              f"reach (mean ratio) {mean(ratios):+.3f}, median {st.median(ratios):+.3f}, "
              f"sum realised / sum commanded "
              f"{sum(f(r,'catch_realised') for r in C) / sum(f(r,'catch_commanded') for r in C):+.3f}")
        A = [r for r in R if r['catch_time']]
        print(f"  catch steps with an early release: {sum(early(r) for r in A)} of {len(A)} "
              f"(counted: {sum(early(r) for r in C)} of {len(C)}), mean lead "
              f"{mean(f(r,'catch_lead') for r in A if early(r)):.3f} s; mean catch dT "
              f"{mean(f(r,'catch_dt') for r in A):+.3f} s; under-way steps with an early release "
              f"{sum(early(r,'under') for r in A)}")
        groups = [
            ('early release, last command against the push',
             [r for r in C if early(r) and f(r, 'catch_commanded') * sgn < 0]),
            ('early release, last command along the push',
             [r for r in C if early(r) and f(r, 'catch_commanded') * sgn > 0]),
            ('no early release, duration < 0.2 s',
             [r for r in C if not early(r) and f(r, 'catch_duration') < 0.2]),
            ('no early release, duration >= 0.2 s',
             [r for r in C if not early(r) and f(r, 'catch_duration') >= 0.2]),
        ]
        for lab, S in groups:
            if not S:
                print(f"  {lab}: 0")
                continue
            m = lambda k: mean(f(r, k) for r in S)
            print(f"  {lab}: {len(S)}, mean ratio {m('ratio'):+.3f}, share of the reach "
                  f"{sum(f(r,'ratio') for r in S)/len(C):+.3f}, ratio<0 in {sum(1 for r in S if f(r,'ratio')<0)}")
            print(f"    command at the first tick {m('catch_first_commanded'):+.3f}, at release "
                  f"{m('catch_released'):+.3f}, at the last tick {m('catch_commanded'):+.3f} (dF "
                  f"{m('catch_df'):+.3f}, dT {m('catch_dt'):+.3f}); realised {m('catch_realised'):+.3f}; "
                  f"lead {m('catch_lead'):.3f} s; duration {m('catch_duration'):.3f} s; impulse {m('impulse'):.2f} Ns")
        # The reach with the command at release (where the generator let the swing foot go).
        Rr = [r for r in A if r['counted'] == 'true' or (
            abs(f(r, 'catch_released') - f(r, 'catch_f_r')) >= 0.1 and r['counted'] == 'true')]
        rel = [f(r, 'catch_realised') / f(r, 'catch_released') for r in C
               if abs(f(r, 'catch_released') - f(r, 'catch_f_r')) >= 0.1]
        print(f"  reach against the command at release (same pushes, released command >= 0.1 m "
              f"beyond F_R: {len(rel)}): mean {mean(rel):+.3f}, median {st.median(rel):+.3f}")
        along = [f(r, 'ratio') for r in C if f(r, 'catch_commanded') * sgn > 0]
        print(f"  reach over the catch steps commanded along the push ({len(along)}): {mean(along):+.3f}")
        for lab, lo, hi in [('dT >= -0.05', -0.05, 9), ('-0.10 <= dT < -0.05', -0.10, -0.05),
                            ('dT < -0.10', -9, -0.10)]:
            S = [r for r in A if lo <= f(r, 'catch_dt') < hi]
            if S and w == 'learned':
                print(f"  catch steps with {lab}: {len(S)}, early release in {sum(early(r) for r in S)} "
                      f"({sum(early(r) for r in S)/len(S):.0%}), duration {mean(f(r,'catch_duration') for r in S):.3f} s")
