# Judge, seeds 5-9, C (400 pushes), --learn step-x,step-time, against the default (results-archive/catch-step-reach):
# python3 judge.py (configs/landing.toml, dirs judge-*) or python3 judge.py judge-lift0.3 (lift0.3.toml)
import os,sys,statistics as st
HERE=os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0,os.path.dirname(HERE))
from paired import i50,mean_h as ci,summary  # noqa: E402  (ci: mean and 95% half-width, nan for one)
A=os.path.join(HERE,'..','catch-step-reach')
PREFIX=sys.argv[1] if len(sys.argv)>1 else 'judge'
def get(d):
    f=summary(d); r=f['catch_step_reach']
    return r['model'], i50(f,'model'), r['learned'], i50(f,'learned')
for dir in ['forward','backward']:
    rows=[]
    for s in range(5,10):
        d=os.path.join(HERE,f'{PREFIX}-{dir}-s{s}'); b=f'{A}/C-step-x_step-time-{dir}-s{s}'; bx=f'{A}/C-step-x-{dir}-s{s}'
        if not os.path.exists(d+'/summary.json'): continue
        rows.append((s,get(d),get(b),get(bx)))
    if not rows: continue
    for s,n,b,bx in rows:
        print(f"{dir} s{s}: new model reach {n[0]:.3f} I50 {n[1]:.2f} | default model reach {b[0]:.3f} I50 {b[1]:.2f} | new xt L/M {n[3]/n[1]:.3f} default xt L/M {b[3]/b[1]:.3f}")
    m,h=ci([n[1]/b[1] for s,n,b,bx in rows]); print(f"{dir}: model I50 new/default {m:.3f} +- {h:.3f}; reach new {st.mean(n[0] for s,n,b,bx in rows):.3f} default {st.mean(b[0] for s,n,b,bx in rows):.3f}")
    m,h=ci([n[3]/n[1] for s,n,b,bx in rows]); print(f"{dir}: xt learner / model (new) {m:.3f} +- {h:.3f}; learned reach {st.mean(n[2] for s,n,b,bx in rows):.3f}")
    m,h=ci([n[3]/b[3] for s,n,b,bx in rows]); print(f"{dir}: xt learner new / xt learner default {m:.3f} +- {h:.3f}")
    m,h=ci([n[3]/b[1] for s,n,b,bx in rows]); print(f"{dir}: xt learner new / default model {m:.3f} +- {h:.3f}")
