#!/usr/bin/env python3
"""The primary pair's champions' size and regularity (lsystem against direct, or the two
conditions named after the file) from a comparison's summary.csv: two-sided Mann-Whitney U with a permutation p (random splits of the
pooled values, ties at mean ranks), A12, and Holm's correction over the four body outcomes
(parts, repeated, mirrored, bytes per part), and each condition's wall time.

    python3 benches/primary-body-tests.py runs/cmp-hornby-pollack/summary.csv
    python3 benches/primary-body-tests.py runs/cmp-repeat/summary.csv with without
"""
import csv, random, sys, statistics as st

rows = list(csv.DictReader(open(sys.argv[1])))
first, second = sys.argv[2:4] if len(sys.argv) >= 4 else ('lsystem', 'direct')
A = [r for r in rows if r['condition'] == first]
B = [r for r in rows if r['condition'] == second]

def u_of(x, y):
    return sum((xi > yi) + 0.5 * (xi == yi) for xi in x for yi in y)

def perm_p(a, b, n=20000, seed=1):
    rng = random.Random(seed)
    pooled = a + b
    mean = len(a) * len(b) / 2
    obs = abs(u_of(a, b) - mean)
    hits = 0
    for _ in range(n):
        rng.shuffle(pooled)
        x, y = pooled[:len(a)], pooled[len(a):]
        hits += abs(u_of(x, y) - mean) >= obs - 1e-9
    return (hits + 1) / (n + 1)

keys = ['parts', 'repeated', 'mirrored', 'bytes_per_part']
res = []
for k in keys:
    a = [float(r[k]) for r in A]; b = [float(r[k]) for r in B]
    u = u_of(a, b)
    res.append((k, u, perm_p(a, b), u / (len(a) * len(b)), st.median(a), st.median(b)))
order = sorted(range(len(res)), key=lambda i: res[i][2])
holm, running = {}, 0.0
for rank, i in enumerate(order):
    running = max(running, min(1.0, (len(res) - rank) * res[i][2]))
    holm[i] = running
print(f'outcome\tU\tp\tHolm p\tA12\tmedian {first}\tmedian {second}')
for i, (k, u, p, a12, ma, mb) in enumerate(res):
    print(f'{k}\t{u:.1f}\t{p:.4f}\t{holm[i]:.4f}\t{a12:.3f}\t{ma:.3g}\t{mb:.3g}')
for c, X in ((first, A), (second, B)):
    print(c, 'replicates', len(X), 'wall core-minutes', round(sum(float(r['wall_seconds']) for r in X) / 60, 1))
