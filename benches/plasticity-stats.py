#!/usr/bin/env python3
# The figures of docs/results/plasticity.md beyond the comparison's report: per condition,
# the gap between a champion's fitness under the two cues (plastic and fixed: flat against
# steps; random-cue: the mean over both grounds under cue 0 against under cue 1), its median,
# and exact two-sided Mann-Whitney tests of the gaps between conditions.
#   ontogeny runs plasticity runs/plasticity --csv > norms.csv
#   python3 benches/plasticity-stats.py norms.csv
import csv, itertools, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1] if len(sys.argv) > 1 else 'docs/compare/plasticity/norms.csv')))
gaps = {}
for (cond, run), group in itertools.groupby(rows, key=lambda r: (r['condition'], r['run'])):
    by_cue = {}
    for r in group:
        by_cue.setdefault(r['environment'], []).append(float(r['fitness']))
    means = [statistics.mean(v) for _, v in sorted(by_cue.items())]
    gaps.setdefault(cond, []).append(abs(means[0] - means[1]))
for cond, g in gaps.items():
    print(f"{cond}: gap between cues per champion {[round(x, 2) for x in g]}, median {statistics.median(g):.2f}")
def exact_mw(a, b):
    pooled = a + b
    u_of = lambda x, y: sum((xi > yi) + 0.5 * (xi == yi) for xi in x for yi in y)
    u, mean = u_of(a, b), len(a) * len(b) / 2
    extreme = total = 0
    for idx in itertools.combinations(range(len(pooled)), len(a)):
        chosen = set(idx)
        x = [pooled[i] for i in idx]
        y = [pooled[i] for i in range(len(pooled)) if i not in chosen]
        total += 1
        extreme += abs(u_of(x, y) - mean) >= abs(u - mean) - 1e-9
    return u, extreme / total, u / (len(a) * len(b))
names = list(gaps)
for a, b in itertools.combinations(names, 2):
    u, p, a12 = exact_mw(gaps[a], gaps[b])
    print(f"gap {a} vs {b}: U = {u:.0f}, p = {p:.4f}, A12 = {a12:.2f}")
