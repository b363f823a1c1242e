#!/usr/bin/env python3
# The figures of docs/results/plasticity.md beyond the comparison's report: per condition,
# the gap between a champion's fitness under the two cues (plastic and fixed: flat against
# steps; random-cue: the mean over both grounds under cue 0 against under cue 1), its median,
# and exact two-sided Mann-Whitney tests of the gaps between conditions.
#   ontogeny runs plasticity runs/plasticity --csv > norms.csv
#   python3 benches/plasticity-stats.py norms.csv
import csv, itertools, statistics, sys, os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exact_tests import exact_mw

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
names = list(gaps)
for a, b in itertools.combinations(names, 2):
    u, p, a12 = exact_mw(gaps[a], gaps[b])
    print(f"gap {a} vs {b}: U = {u:.0f}, p = {p:.4f}, A12 = {a12:.2f}")
