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
import csv, itertools, statistics, sys, os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exact_tests import exact_mw, signed_rank, holm

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
final = {c: of(c, last, noises[0], 'mutation_mean_volume_change') for c in conditions}
for a, b in itertools.combinations(conditions, 2):
    u, p, a12 = exact_mw(final[a], final[b])
    print(f'generation {last} mutants |dV|/V {a} vs {b}: U = {u:.1f}, p = {p:.4f}, A12 = {a12:.2f}')
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
