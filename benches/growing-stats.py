#!/usr/bin/env python3
# The growing-while-walking results page's statistics, from the re-walks of each condition's
# champions (benches/rewalk.sh with STRENGTH=9000: "perturbed" is every joint 10% weaker)
# and Kriegman's measure per generation (`ontogeny runs growth DIR --csv`):
#   python3 benches/growing-stats.py REWALK.csv [REWALK.csv ...] --growth GROWTH.csv
# Prints, per condition: the champions' stored distance and the share of it each kept with
# every joint 10% weaker and at the fine reference (medians and each replicate), the exact
# two-sided Mann-Whitney test of during against before on each share (Holm over the two);
# then, for the growing condition, how the best individual's growth during its walk (body:
# parts, length; brain: neurons, links) changed over the generations: medians over the runs
# of the first and last five generations, and per run Spearman's correlation of each measure
# with the generation (how many runs fell, how many rose).
import csv, statistics, sys, os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exact_tests import exact_mw, holm, spearman

args = sys.argv[1:]
growth = None
if "--growth" in args:
    i = args.index("--growth")
    growth = args[i + 1]
    del args[i:i + 2]

rows = [r for f in args for r in csv.DictReader(open(f))]
def num(x):
    try:
        v = float(x)
        return v if v > -999999 else None
    except ValueError:
        return None

shares = {}
for r in rows:
    stored = num(r["stored"])
    c = shares.setdefault(r["encoding"], {"stored": [], "weaker": [], "fine": [], "reps": []})
    c["reps"].append(r["rep"])
    c["stored"].append(stored)
    for k in ("weaker", "fine"):
        v = num(r["perturbed" if k == "weaker" else k])
        c[k].append(None if stored in (None, 0) or v is None else v / stored)

for cond, c in shares.items():
    print(f"## {cond}: {len(c['reps'])} champions")
    print("replicate,stored (m),weaker share,fine share")
    for rep, s, w, f in zip(c["reps"], c["stored"], c["weaker"], c["fine"]):
        fmt = lambda x: "NA" if x is None else f"{x:.2f}"
        print(f"{rep},{fmt(s)},{fmt(w)},{fmt(f)}")
    for k in ("stored", "weaker", "fine"):
        vals = [x for x in c[k] if x is not None]
        print(f"median {k}: {statistics.median(vals):.2f} (n = {len(vals)})")
    print()

if {"during", "before"} <= shares.keys():
    tests = []
    for k in ("weaker", "fine"):
        a = [x for x in shares["during"][k] if x is not None]
        b = [x for x in shares["before"][k] if x is not None]
        u, p, auc = exact_mw(a, b)
        tests.append((k, u, p, auc, len(a), len(b)))
    adjusted = holm([t[2] for t in tests])
    print("share kept, during against before (exact two-sided Mann-Whitney, Holm over 2):")
    for (k, u, p, auc, na, nb), ph in zip(tests, adjusted):
        print(f"  {k}: U = {u:g}, p = {p:.3f}, Holm {ph:.3f}, P(during > before) = {auc:.2f} ({na} against {nb})")
    print()

if growth:
    runs = {}
    for r in csv.DictReader(open(growth)):
        if r["condition"] != "during":
            continue
        runs.setdefault(r["run"], []).append(r)
    runs = {k: v for k, v in runs.items() if len(v) >= 10}
    measures = ("champion_parts", "champion_length", "champion_neurons", "champion_links")
    print(f"Kriegman's measure, best individual of each generation, {len(runs)} runs:")
    last = min(len(v) for v in runs.values())
    for m in measures:
        first5 = [statistics.mean(float(r[m]) for r in v[:5]) for v in runs.values()]
        last5 = [statistics.mean(float(r[m]) for r in v[last - 5:last]) for v in runs.values()]
        rhos = []
        for v in runs.values():
            xs = [float(r["generation"]) for r in v[:last]]
            ys = [float(r[m]) for r in v[:last]]
            if len(set(ys)) > 1:
                rhos.append(spearman(xs, ys))
        fell = sum(r < 0 for r in rhos)
        rose = sum(r > 0 for r in rhos)
        flat = len(runs) - len(rhos)
        print(f"  {m}: median of first 5 generations {statistics.median(first5):.2f}, of last 5 "
              f"(to generation {last - 1}) {statistics.median(last5):.2f}; Spearman with generation: "
              f"{fell} runs fell, {rose} rose, {flat} unchanged; median rho "
              f"{statistics.median(rhos) if rhos else float('nan'):.2f}")
