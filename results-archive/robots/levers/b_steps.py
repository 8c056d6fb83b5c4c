import csv,json,statistics as st,sys
for d in sys.argv[1:]:
    s=json.load(open(d+'/summary.json'))
    out=[d.split('/')[-1], 'falls', s['falls']['falls']['model'], s['falls']['falls']['learned'], 'ret', round(s['return_time_by_step_s']['model'],2), round(s['return_time_by_step_s']['learned'],2)]
    for c in ['model','learned']:
        rows=[r for r in csv.DictReader(open(d+'/disturbance_steps.csv')) if r['controller']==c and float(r['time_s'])>30]
        out+= [c, round(st.median(float(r['f_e_m']) for r in rows),4)]
    print(*out)
