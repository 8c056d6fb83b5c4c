import json,os,sys
levers=sys.argv[1:] or ['baseline','gain1.3','lead0.05','gain1.6']
def load(d):
    p=os.path.join(d,'summary.json')
    if not os.path.exists(p): return None
    j=json.load(open(p)); m=j['controllers']['model']
    return j['catch_step_reach']['model'], m['impulse_at_50pct_fall_ns'], m['falls'], m['pushes']
for L in levers:
    print(f"\n### {L} (backward, 200 pushes)\n")
    print("| seed | model reach | model I50 (Ns) | I50 / baseline I50 (same seed) | model falls / pushes |")
    print("|---|---|---|---|---|")
    rs=[];Is=[];qs=[]
    for s in [0,1,2]:
        r=load(f"{L}-s{s}"); b=load(f"baseline-s{s}")
        if r is None: print(f"| {s} | not run | | | |"); continue
        q=r[1]/b[1] if b else float('nan')
        rs.append(r[0]);Is.append(r[1]);qs.append(q)
        print(f"| {s} | {r[0]:.3f} | {r[1]:.2f} | {q:.3f} | {r[2]}/{r[3]} |")
    if rs: print(f"| mean | {sum(rs)/len(rs):.3f} | {sum(Is)/len(Is):.2f} | {sum(qs)/len(qs):.3f} | |")
