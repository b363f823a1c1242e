#!/usr/bin/env python3
"""The step-settings study's figures (docs/results/speed.md, "Why the default is physics at
1/240 s") from its re-walk CSVs (benches/rewalk.sh): per champion, each re-walk's share of the
stored distance (an exploded walk, -999999, counts as 0), their medians by the setting the
champions evolved at, and two-sided Mann-Whitney tests of each setting's shares against the
default's: exact over every split where the smaller sample is small (6 against 6), else by
200,000 random splits (seed 1); and, within each setting's champions, Wilcoxon's signed-rank
test (exact, over every sign flip, counted by sums) of the share kept under the strength
change against the share kept at the fine reference: a walk that survives a change of its
strength but not of the physics learnt the setting's error.
    python3 benches/step-settings-stats.py docs/compare/step-settings
"""
import csv, os, random, statistics, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exact_tests import exact_mw, signed_rank

KINDS = ["perturbed", "fine", "fine16"]


def shares(path):
    out = {k: [] for k in KINDS}
    for row in csv.DictReader(open(path)):
        stored = float(row["stored"])
        for k in KINDS:
            try:
                v = float(row[k])
            except ValueError:
                v = -999999.0
            out[k].append(0.0 if v <= -999999.0 else max(v, 0.0) / stored)
    return out


def permutation_mw(a, b, draws=200_000, seed=1):
    u_of = lambda x, y: sum((xi > yi) + 0.5 * (xi == yi) for xi in x for yi in y)
    u, mean = u_of(a, b), len(a) * len(b) / 2
    pooled, rng, extreme = a + b, random.Random(seed), 0
    for _ in range(draws):
        rng.shuffle(pooled)
        x, y = pooled[: len(a)], pooled[len(a):]
        extreme += abs(u_of(x, y) - mean) >= abs(u - mean) - 1e-9
    return u, extreme / draws, u / (len(a) * len(b))


d = sys.argv[1] if len(sys.argv) > 1 else "docs/compare/step-settings"
sets = [("fast", "rewalk-fast.csv"), ("3x4x1/4x8", "rewalk-3x4.csv"), ("default", "rewalk-default.csv")]
data = {name: shares(os.path.join(d, f)) for name, f in sets}
print("evolved at | champions | " + " | ".join(f"median share {k}" for k in KINDS))
for name, _ in sets:
    s = data[name]
    print(f"{name} | {len(s['fine'])} | " + " | ".join(f"{statistics.median(s[k]):.2f}" for k in KINDS))
for name in ["fast", "3x4x1/4x8"]:
    for k in KINDS:
        a, b = data[name][k], data["default"][k]
        exact = len(a) + len(b) <= 14
        u, p, a12 = exact_mw(a, b) if exact else permutation_mw(a, b)
        how = "exact" if exact else "200,000 random splits"
        print(f"{name} against default, {k}: U {u:.1f}, p {p:.3f} ({how}), A12 {a12:.2f}")
for name, _ in sets:
    s = data[name]
    differences = [a - b for a, b in zip(s["perturbed"], s["fine"])]
    w, p = signed_rank(differences)
    n = sum(1 for x in differences if x != 0)
    print(f"{name}: perturbed against fine, paired: W+ {w:.1f} of {n} nonzero differences, p {p:.2g} (exact)")
