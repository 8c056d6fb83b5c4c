# The counted catch steps of catch_anatomy CSVs as the library counts them (lib_ columns), by realised / commanded: python3 anatomy.py anatomy-backward-s0.csv
import csv, statistics as s, math, sys
for fn in sys.argv[1:]:
  for w in ['model','learned']:
    rows=[r for r in csv.DictReader(open(fn)) if r['walker']==w and r['lib_counted']=='true']
    pts=[(float(r['lib_ratio']),float(r['lib_commanded']),float(r['lib_realised']),float(r['lib_duration']),r) for r in rows]
    print(fn,w,len(pts),"reach %.4f"%s.mean(p[0] for p in pts))
    for lo,hi in [(-99,0),(0,0.5),(0.5,0.8),(0.8,1.0),(1.0,1.2),(1.2,99)]:
        v=[p for p in pts if lo<=p[0]<hi]
        if v: print(f"  [{lo},{hi}) n={len(v)} mean={s.mean(p[0] for p in v):.3f} share={sum(p[0] for p in v)/len(pts):+.3f} cmd={s.mean(p[1] for p in v):+.3f} real={s.mean(p[2] for p in v):+.3f} dur={s.mean(p[3] for p in v):.3f} short(<0.25s)={sum(1 for p in v if p[3]<0.25)}")
    sh=[p for p in pts if p[3]<0.25]
    print("  duration<0.25 s: n=%d share %+.3f; reach without them %.4f"%(len(sh),sum(p[0] for p in sh)/len(pts), s.mean(p[0] for p in pts if p[3]>=0.25)))
