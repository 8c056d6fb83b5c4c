import json,sys,glob,os
for name in sys.argv[1:]:
    m=l=n=0; fs=[]; st={'model':[], 'learned':[]}
    for f in sorted(glob.glob(f'out/{name}/s*/summary.json')):
        d=json.load(open(f)); m+=d['falls']['falls']['model']; l+=d['falls']['falls']['learned']; n+=d['falls']['pushes']['model']
    # realised undisturbed step: from disturbance_steps.csv? skip
    print(f"{name:12s} seeds={len(glob.glob(f'out/{name}/s*/summary.json'))} pushes={n} model={m} learned={l}")
