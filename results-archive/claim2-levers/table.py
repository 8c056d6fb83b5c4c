# Per lever: the return time to F_R of each walker per seed, the binned mean step (m) of the
# 1.0-1.5, 1.5-2.0 and 2.0-2.5 s bins after a push (F_R = 0.2 m, tolerance 0.03 m), falls, and
# the mean of learned - model return time over the seeds.
#   python3 table.py NAME SEEDS      e.g. python3 table.py tr2.5 0,1,2,3,4
import csv, json, statistics, sys
name = sys.argv[1]; seeds = [int(x) for x in sys.argv[2].split(',')]
diffs = []
for s in seeds:
    d = json.load(open(f'{name}-s{s}/summary.json'))
    rows = list(csv.DictReader(open(f'{name}-s{s}/disturbance_aligned.csv')))
    b = {c: [float(r['mean_step_m']) for r in rows if r['controller'] == c] for c in ('model', 'learned')}
    r = d['return_time_s']; f = d['falls']['falls']
    diffs.append(r['learned'] - r['model'])
    print(f"seed {s}: return model {r['model']:.1f} s, learned {r['learned']:.1f} s; bins 1.25/1.75/2.25 s model "
          + ' '.join(f'{x:.3f}' for x in b['model'][2:5]) + ', learned ' + ' '.join(f'{x:.3f}' for x in b['learned'][2:5])
          + f"; falls {f['model']} / {f['learned']}")
print(f'{name}: learned - model return time, mean over seeds {seeds}: {statistics.mean(diffs):+.2f} s')
