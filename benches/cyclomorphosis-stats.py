#!/usr/bin/env python3
# The figures of docs/results/plasticity.md's cyclomorphosis section beyond the comparison's
# report: per condition, each champion's fitness in the open and under the bars, its height as
# built under each cue, whether its body depends on the cue; exact two-sided Mann-Whitney tests
# between the conditions of the height (open cue) and of the fitness under the bars; and, over
# the champions whose body does not depend on the cue, Spearman's correlation of height with
# the fitness lost under the bars (a permutation p).
#   ontogeny runs plasticity runs/cyclomorphosis --csv > norms.csv
#   python3 benches/cyclomorphosis-stats.py norms.csv
import csv, itertools, random, statistics, sys, os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exact_tests import exact_mw, ranks, spearman

rows = list(csv.DictReader(open(sys.argv[1] if len(sys.argv) > 1 else 'docs/compare/cyclomorphosis/norms.csv')))
champions = {}
for r in rows:
    champions.setdefault((r['condition'], r['run']), {})[r['habitat']] = r
height, bars, lost = {}, {}, ([], [])
for (cond, run), h in champions.items():
    o, b = h['open'], h['bars']
    height.setdefault(cond, []).append(float(o['height']))
    bars.setdefault(cond, []).append(float(b['fitness']))
    print(f"{cond} {run}: open {float(o['fitness']):.2f} m, bars {float(b['fitness']):.2f} m, "
          f"height {float(o['height']):.3f} -> {float(b['height']):.3f} m, depends on cue {o['depends_on_cue']}")
    if o['depends_on_cue'] != 'true':
        lost[0].append(float(o['height']))
        lost[1].append(float(o['fitness']) - float(b['fitness']))
for cond in height:
    print(f"{cond}: median height {statistics.median(height[cond]):.3f} m, median fitness under the bars {statistics.median(bars[cond]):.2f} m")
names = list(height)
for a, b in itertools.combinations(names, 2):
    u, p, a12 = exact_mw(height[a], height[b])
    print(f"height {a} vs {b}: U = {u:.1f}, p = {p:.4f}, A12 = {a12:.2f}")
    u, p, a12 = exact_mw(bars[a], bars[b])
    print(f"fitness under the bars {a} vs {b}: U = {u:.1f}, p = {p:.4f}, A12 = {a12:.2f}")
rho = spearman(*lost)
random.seed(1)
shuffled, extreme = list(lost[1]), 0
for _ in range(20000):
    random.shuffle(shuffled)
    extreme += abs(spearman(lost[0], shuffled)) >= abs(rho) - 1e-12
print(f"height against fitness lost under the bars, {len(lost[0])} champions whose body does not depend on the cue: "
      f"Spearman {rho:.2f}, permutation p = {extreme / 20000:.3f}")
