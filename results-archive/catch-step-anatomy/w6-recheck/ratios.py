"""Learned / model I50 per seed and direction from the summaries here (C-W6dz06-*) and, for
comparison, results-archive/step-time-levers/C-{X6,W6}-* (run from this folder)."""
import json, os
base = '../../step-time-levers'
for lever, root in [('W6dz06', '.'), ('W6', base), ('X6', base)]:
    for d in ['forward', 'backward']:
        out = []
        for s in range(5):
            p = f"{root}/C-{lever}-{d}-s{s}/summary.json"
            if not os.path.exists(p):
                out.append('-')
                continue
            c = json.load(open(p))['controllers']
            m, l = c['model']['impulse_at_50pct_fall_ns'], c['learned']['impulse_at_50pct_fall_ns']
            out.append((m, l, l / m))
        r = [x[2] for x in out if x != '-']
        print(f"{lever} {d}: " + ' '.join('-' if x == '-' else f"s{i} {x[1]:.2f}/{x[0]:.2f}={x[2]:.3f}"
              for i, x in enumerate(out)) + (f"; mean ratio {sum(r)/len(r):.3f} ({len(r)} seeds)" if r else ''))
