# Per lever and direction (seeds 0-2, C with 200 pushes, --learn step-x,step-time): the model's catch step reach and I50 (and I50 over the default's), the learner's I50 over the model's (L/M) and reach.
# python3 levers.py [LEVER ...] (default: all; the first is the reference); SEEDS=0,1,2,3,4 for other seeds
import json,sys,os,statistics as st
HERE=os.path.dirname(os.path.abspath(__file__))
def get(d):
    f=json.load(open(os.path.join(d,'summary.json')))
    c=f['controllers']; r=f['catch_step_reach']
    return r['model'], c['model']['impulse_at_50pct_fall_ns'], r['learned'], c['learned']['impulse_at_50pct_fall_ns']
SEEDS=[int(x) for x in os.environ.get("SEEDS","0,1,2").split(",")]
levers=sys.argv[1:] or ['default','wait0.1','early0.5','early0.2','early0.5wait0.1','gain1.3early0.5','lift0.3','lift0.6','early0.5lift0.3','band0.02','band0.05']
for dir in ['forward','backward']:
    base={}
    for lever in levers:
        rows=[]
        for s in SEEDS:
            d=os.path.join(HERE,f'xt-{lever}-{dir}-s{s}')
            if not os.path.exists(d+'/summary.json'): continue
            rows.append((s,get(d)))
        if not rows: continue
        if lever==levers[0]: base={s:m for s,m in rows}
        line=" ".join(f"s{s}: reach {m[0]:.3f} I50 {m[1]:.2f} L/M {m[3]/m[1]:.3f} Lreach {m[2]:.3f}" for s,m in rows)
        rel=[m[1]/base[s][1] for s,m in rows if s in base]
        print(f"{dir:8} {lever:10} mean reach {st.mean(m[0] for s,m in rows):.3f} I50 {st.mean(m[1] for s,m in rows):.2f} (x{st.mean(rel):.3f} of {levers[0]}) L/M {st.mean(m[3]/m[1] for s,m in rows):.3f} | {line}")
