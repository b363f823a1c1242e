#!/usr/bin/env python3
# The figures of docs/results/plasticity.md's cyclomorphosis section beyond the comparison's
# report: per condition, each champion's fitness in the open and under the bars, its height as
# built under each cue, whether its body depends on the cue; exact two-sided Mann-Whitney tests
# between the conditions of the height (open cue) and of the fitness under the bars; and, over
# the champions whose body does not depend on the cue, Spearman's correlation of height with
# the fitness lost under the bars (a permutation p).
#   ontogeny runs plasticity runs/cyclomorphosis --csv > norms.csv
#   python3 benches/cyclomorphosis-stats.py norms.csv
import csv, itertools, random, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1] if len(sys.argv) > 1 else 'docs/compare/cyclomorphosis/norms.csv')))
champions = {}
for r in rows:
    champions.setdefault((r['condition'], r['run']), {})[r['habitat']] = r
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
def ranks(v):
    order = sorted(range(len(v)), key=lambda i: v[i])
    out, i = [0.0] * len(v), 0
    while i < len(v):
        j = i
        while j + 1 < len(v) and v[order[j + 1]] == v[order[i]]:
            j += 1
        for k in range(i, j + 1):
            out[order[k]] = (i + j) / 2 + 1
        i = j + 1
    return out
def spearman(x, y):
    rx, ry = ranks(x), ranks(y)
    mx, my = statistics.mean(rx), statistics.mean(ry)
    num = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    return num / (sum((a - mx) ** 2 for a in rx) * sum((b - my) ** 2 for b in ry)) ** 0.5
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
