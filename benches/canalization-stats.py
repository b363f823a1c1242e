#!/usr/bin/env python3
# The canalization figures of docs/results/plasticity.md: per condition and generation
# measured, the share of champions whose body any noisy array changed (at each noise level)
# and the median over champions of the mutants' |ΔV|/V and share changed; exact two-sided
# Mann-Whitney tests between conditions of the last generation's mutational |ΔV|/V, and exact
# two-sided sign-flip (Wilcoxon signed-rank) tests of the change of the mutants' |ΔV|/V and of
# the share of mutants that change the body from generation 0 to the last within each
# condition (Holm over the conditions).
#   for c in plastic fixed random-cue; do for r in $(seq 1 10); do for n in 0.05 0.25 0.45; do
#     ontogeny runs canalization runs/plasticity/$c/rep-$r --samples 20 --every 5 --noise $n --csv \
#       | sed "1s/^/condition,run,noise,/;2,\$s/^/$c,rep-$r,$n,/"; done; done; done \
#     | awk 'NR == 1 || !/^condition/' > canalization.csv
#   python3 benches/canalization-stats.py canalization.csv
import csv, itertools, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1] if len(sys.argv) > 1 else 'docs/compare/plasticity/canalization.csv')))
conditions = list(dict.fromkeys(r['condition'] for r in rows))
noises = sorted(set(r['noise'] for r in rows), key=float)
generations = sorted(set(int(r['generation']) for r in rows))
last = generations[-1]
def of(condition, generation, noise, column):
    return [float(r[column]) for r in rows if r['condition'] == condition and int(r['generation']) == generation
            and r['noise'] == noise and r[column] != '']
print('condition generation ' + ' '.join(f'noise±{n}:changed' for n in noises) + ' mutants:changed mutants:|dV|/V')
for c in conditions:
    for g in generations:
        noise = ' '.join(f'{sum(x > 0 for x in of(c, g, n, "noise_changed"))}/{len(of(c, g, n, "noise_changed"))}' for n in noises)
        changed = statistics.median(of(c, g, noises[0], 'mutation_changed'))
        dv = statistics.median(of(c, g, noises[0], 'mutation_mean_volume_change'))
        print(f'{c} {g} {noise} {changed:.2f} {dv:.3f}')
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
def signed_rank(d):
    d = [x for x in d if x != 0]
    # Ranks of |d|, ties given their mean rank; the exact distribution over every sign flip.
    order = sorted(range(len(d)), key=lambda i: abs(d[i]))
    ranks, i = [0.0] * len(d), 0
    while i < len(d):
        j = i
        while j + 1 < len(d) and abs(d[order[j + 1]]) == abs(d[order[i]]):
            j += 1
        for k in range(i, j + 1):
            ranks[order[k]] = (i + j) / 2 + 1
        i = j + 1
    w = sum(r for r, x in zip(ranks, d) if x > 0)
    mean = sum(ranks) / 2
    extreme = total = 0
    for signs in itertools.product([0, 1], repeat=len(d)):
        total += 1
        extreme += abs(sum(r for r, s in zip(ranks, signs) if s) - mean) >= abs(w - mean) - 1e-9
    return w, extreme / total
final = {c: of(c, last, noises[0], 'mutation_mean_volume_change') for c in conditions}
for a, b in itertools.combinations(conditions, 2):
    u, p, a12 = exact_mw(final[a], final[b])
    print(f'generation {last} mutants |dV|/V {a} vs {b}: U = {u:.1f}, p = {p:.4f}, A12 = {a12:.2f}')
def holm(ps):
    order = sorted(range(len(ps)), key=lambda i: ps[i])
    adjusted, running = [0.0] * len(ps), 0.0
    for position, i in enumerate(order):
        running = max(running, min(1.0, (len(ps) - position) * ps[i]))
        adjusted[i] = running
    return adjusted
for column, name in [('mutation_mean_volume_change', 'mutants |dV|/V'), ('mutation_changed', 'share of mutants changed')]:
    tests = []
    for c in conditions:
        by_run = lambda g: {r['run']: float(r[column]) for r in rows
                            if r['condition'] == c and int(r['generation']) == g and r['noise'] == noises[0]}
        first, end = by_run(0), by_run(last)
        differences = [end[k] - first[k] for k in first]
        w, p = signed_rank(differences)
        tests.append((c, w, p, sum(d != 0 for d in differences), sum(d > 0 for d in differences)))
    for (c, w, p, n, up), adjusted in zip(tests, holm([t[2] for t in tests])):
        print(f'{c}: {name} generation 0 -> {last}: {up} of {n} non-zero changes up, W+ = {w:.1f}, '
              f'p = {p:.4f}, Holm over the conditions {adjusted:.4f}')
