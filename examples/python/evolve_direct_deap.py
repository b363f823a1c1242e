#!/usr/bin/env python3
"""Evolve a walker's direct genome with an external optimiser: DEAP's genetic algorithm,
with Ontogeny's `evaluate_many` as its fitness function.

A vector of 14 numbers in [0, 1] sets a quadruped's proportions and its gait: the body's
segment length and width, the legs' thickness and lengths, the oscillator's bias, and the
weight of the oscillator's output on each of the eight joints. `direct_genome` writes the
vector as a direct genome (an `.lsys` file holding an axiom alone: the body and brain
commands, read by the builder as they are), `ontogeny.genome` develops it, and
`ontogeny.evaluate_many` walks the whole population in parallel on the Rust side.

    pip install ./python deap
    python examples/python/evolve_direct_deap.py            # about a minute on 2 cores
    python examples/python/evolve_direct_deap.py --pop 64 --gens 30 --out best.lsys

The best genome is written with `--out`; `ontogeny eval best.lsys --task walker` walks it
again from the command line, with the same fitness at the same settings.
"""

import argparse
import random
import time

from deap import base, creator, tools

import ontogeny

GENES = 14


def scale(x: float, low: float, high: float) -> float:
    """`x` in [0, 1] mapped to [low, high], rounded to 4 decimals (as a genome is written)."""
    return round(low + (high - low) * min(max(x, 0.0), 1.0), 4)


def direct_genome(x) -> str:
    """The direct genome of the vector `x`: a body of three segments carrying two pairs of
    legs (a shoulder and a hip each), every joint driven by the one oscillator with its own
    weight."""
    segment, body_width = scale(x[0], 0.2, 0.6), scale(x[1], 0.2, 0.4)
    leg_width = scale(x[2], 0.1, 0.25)
    upper, lower = scale(x[3], 0.15, 0.45), scale(x[4], 0.15, 0.5)
    bias = scale(x[5], 0.0, 1.0)
    weights = [scale(w, -1.0, 1.0) for w in x[6:14]]

    def leg(side: str, turn: int, shoulder: float, hip: float) -> str:
        return (
            f"[ {side}(1) width({leg_width}) thickness({leg_width}) revolute1 forward({upper}) "
            f"output({shoulder}) right({turn}) down(1) revolute1 forward({lower}) output({hip}) ]"
        )

    w = weights
    front = leg("left", 1, w[0], w[1]) + " " + leg("right", -1, w[2], w[3])
    rear = leg("left", 1, w[4], w[5]) + " " + leg("right", -1, w[6], w[7])
    return (
        "# A direct genome written by examples/python/evolve_direct_deap.py\n"
        f"axiom: cut bias({bias}) width({body_width}) thickness(0.1) forward({segment}) {front} "
        f"forward({segment}) forward({segment}) {rear}\n"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pop", type=int, default=32, help="individuals per generation")
    parser.add_argument("--gens", type=int, default=20, help="generations")
    parser.add_argument("--seconds", type=float, default=10.0, help="seconds of walking")
    parser.add_argument("--setting", default="fast", help="the step setting (fast, default, fine)")
    parser.add_argument("--threads", type=int, default=None, help="worker threads (default: every core)")
    parser.add_argument("--seed", type=int, default=1, help="the optimiser's seed")
    parser.add_argument("--out", help="write the best genome to this .lsys file")
    args = parser.parse_args()
    random.seed(args.seed)

    creator.create("FitnessMax", base.Fitness, weights=(1.0,))
    creator.create("Individual", list, fitness=creator.FitnessMax)
    toolbox = base.Toolbox()
    toolbox.register("individual", tools.initRepeat, creator.Individual, random.random, GENES)
    toolbox.register("population", tools.initRepeat, list, toolbox.individual)
    toolbox.register("mate", tools.cxBlend, alpha=0.3)
    toolbox.register("mutate", tools.mutGaussian, mu=0.0, sigma=0.15, indpb=0.2)
    toolbox.register("select", tools.selTournament, tournsize=3)

    def evaluate_all(individuals) -> int:
        """Every individual's fitness, from one `evaluate_many` call (in parallel, in order)."""
        creatures = [ontogeny.genome(direct_genome(ind), "direct") for ind in individuals]
        results = ontogeny.evaluate_many(
            creatures, "walker", seconds=args.seconds, setting=args.setting, threads=args.threads
        )
        for ind, result in zip(individuals, results):
            ind.fitness.values = (result.fitness,)
        return len(individuals)

    started = time.perf_counter()
    population = toolbox.population(n=args.pop)
    evaluations = evaluate_all(population)
    hall = tools.HallOfFame(1)
    for gen in range(args.gens + 1):
        if gen > 0:
            offspring = [toolbox.clone(i) for i in toolbox.select(population, len(population) - 1)]
            for a, b in zip(offspring[::2], offspring[1::2]):
                if random.random() < 0.6:
                    toolbox.mate(a, b)
                    del a.fitness.values, b.fitness.values
            for ind in offspring:
                if random.random() < 0.5:
                    toolbox.mutate(ind)
                    del ind.fitness.values
                ind[:] = [min(max(g, 0.0), 1.0) for g in ind]
            fresh = [i for i in offspring if not i.fitness.valid]
            evaluations += evaluate_all(fresh)
            population = [toolbox.clone(hall[0])] + offspring  # the best so far is kept
        hall.update(population)
        fits = [i.fitness.values[0] for i in population]
        valid = [f for f in fits if f > -999999]
        mean = sum(valid) / len(valid) if valid else float("nan")
        print(f"generation {gen}: best {max(fits):.4f}  mean {mean:.4f}  valid {len(valid)}/{len(fits)}")
    wall = time.perf_counter() - started

    best = hall[0]
    text = direct_genome(best)
    check = ontogeny.evaluate(ontogeny.genome(text, "direct"), "walker", seconds=args.seconds, setting=args.setting)
    fine = ontogeny.evaluate(ontogeny.genome(text, "direct"), "walker", seconds=args.seconds, setting="fine")
    print(f"{evaluations} evaluations in {wall:.1f} s ({evaluations / wall:.1f} evaluations/s)")
    print(f"best: fitness {check.fitness:.4f} ({check.status}), D_w {check.terms.get('D_w', 0):.3f} m; "
          f"at the fine setting {fine.fitness:.4f} ({fine.status})")
    print(text.strip().splitlines()[-1])
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
