#!/usr/bin/env python3
# Exact tests the results pages' scripts share: two-sided Mann-Whitney over every split,
# Wilcoxon's signed-rank over every sign flip (ties at their mean rank; counted by sums), Spearman's
# correlation on mean ranks, and Holm's correction.
import itertools, statistics

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

def signed_rank(d):
    d = [x for x in d if x != 0]
    # Ranks of |d|, ties given their mean rank; the exact distribution over every sign flip,
    # counted by the sums of twice the ranks (integers), so that 40 pairs take no longer than 6.
    order = sorted(range(len(d)), key=lambda i: abs(d[i]))
    twice, i = [0] * len(d), 0
    while i < len(d):
        j = i
        while j + 1 < len(d) and abs(d[order[j + 1]]) == abs(d[order[i]]):
            j += 1
        for k in range(i, j + 1):
            twice[order[k]] = i + j + 2
        i = j + 1
    counts = {0: 1}
    for r in twice:
        grown = dict(counts)
        for total, n in counts.items():
            grown[total + r] = grown.get(total + r, 0) + n
        counts = grown
    w2 = sum(r for r, x in zip(twice, d) if x > 0)
    mean2 = sum(twice) / 2
    extreme = sum(n for total, n in counts.items() if abs(total - mean2) >= abs(w2 - mean2) - 1e-9)
    return w2 / 2, extreme / 2 ** len(d)

def holm(ps):
    order = sorted(range(len(ps)), key=lambda i: ps[i])
    adjusted, running = [0.0] * len(ps), 0.0
    for position, i in enumerate(order):
        running = max(running, min(1.0, (len(ps) - position) * ps[i]))
        adjusted[i] = running
    return adjusted
