#!/usr/bin/env python3
# The figures of docs/results/robustness.md's "Noisy trials on rough ground": each robust
# champion's shares of its stored distance, their medians, exact Mann-Whitney tests against
# the baseline's shares, and the power of ten replicates an arm (by simulation).
#   python3 benches/robustness-stats.py [BASELINE_REWALK ROBUST_SUMMARY ROBUST_REWALK_FLAT]
# (defaults: the files under docs/compare/robustness/).
import csv, itertools, statistics, random, math, sys
d = 'docs/compare/robustness/'
paths = sys.argv[1:4] if len(sys.argv) == 4 else [d + 'baseline/rewalk.csv', d + 'robust/summary.csv', d + 'robust/rewalk-flat.csv']
def rows(p): return list(csv.DictReader(open(p)))
base = rows(paths[0])
summ = {r['replicate']: r for r in rows(paths[1])}
flat = rows(paths[2])
b_fine = [float(r['fine'])/float(r['stored']) for r in base]
b_pert = [float(r['perturbed'])/float(r['stored']) for r in base]
b_f16 = [float(r['fine16'])/float(r['stored']) for r in base]
R = []
for r in flat:
    rep = r['rep'].split('-')[1]; s = summ[rep]
    st = float(s['best_fitness']); own_fine = float(s['best_fine'])
    R.append(dict(rep=rep, stored=st, own_fine=own_fine/st, flat=float(r['stored'])/st,
                  pert=float(r['perturbed'])/st, fine=float(r['fine'])/st, f16=float(r['fine16'])/st,
                  flat_m=float(r['stored']), fine_m=float(r['fine']), parts=s['parts']))
for x in R: print(x['rep'], '%.2f'%x['stored'], '%.2f'%x['flat_m'], '%.2f'%x['own_fine'], '%.2f'%x['flat'], '%.2f'%x['pert'], '%.2f'%x['fine'], '%.2f'%x['f16'], x['parts'])
med = statistics.median
print('median stored', med([x['stored'] for x in R]), 'flat m', med([x['flat_m'] for x in R]), 'flat fine m', med([x['fine_m'] for x in R]))
for k in ['own_fine','flat','pert','fine','f16']:
    print(k, 'median %.3f'%med([x[k] for x in R]), 'under 0.8:', sum(x[k]<0.8 for x in R))
print('baseline fine median %.3f pert %.3f f16 %.3f'%(med(b_fine),med(b_pert),med(b_f16)), 'base stored median', med([float(r['stored']) for r in base]), 'base fine m', med([float(r['fine']) for r in base]))
def mwu(a,b):
    n=len(a); allv=a+b
    def U(x,y): return sum((xi>yi)+0.5*(xi==yi) for xi in x for yi in y)
    u=U(a,b); mean=n*len(b)/2
    cnt=0; tot=0
    for idx in itertools.combinations(range(len(allv)), n):
        s=set(idx); x=[allv[i] for i in idx]; y=[allv[i] for i in range(len(allv)) if i not in s]
        tot+=1
        if abs(U(x,y)-mean) >= abs(u-mean)-1e-9: cnt+=1
    return u, cnt/tot, u/(n*len(b))
for name,a,b in [('fine share robust(own) vs base', [x['own_fine'] for x in R], b_fine),
                 ('fine share robust(flat) vs base', [x['fine'] for x in R], b_fine),
                 ('perturbed share robust(flat) vs base', [x['pert'] for x in R], b_pert),
                 ('16x8 share robust(flat) vs base', [x['f16'] for x in R], b_f16),
                 ('fine distance robust(flat) vs base', [x['fine_m'] for x in R], [float(r['fine']) for r in base])]:
    u,p,a12=mwu(a,b); print(name, 'U=%.1f p=%.4f A12=%.2f'%(u,p,a12))
# power of the exact two-sided MW test at n=10 each, alpha 0.05, normal shift
random.seed(1)
def power(d, n=10, sims=2000):
    # critical U from exact null: compute via normal approx threshold from simulation of null
    hits=0
    for _ in range(sims):
        a=[random.gauss(d,1) for _ in range(n)]; b=[random.gauss(0,1) for _ in range(n)]
        u=sum((x>y) for x in a for y in b)
        if u>=77 or u<=23: hits+=1   # exact two-sided 5% critical values for n=m=10 (U<=23)
    return hits/sims
for d in [0.5,0.78,1.0,1.3]:
    a12 = 0.5*(1+math.erf(d/2)) 
    print('shift %.2f sd (A12 %.2f): power %.2f'%(d, a12, power(d)))
