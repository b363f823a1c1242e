#!/usr/bin/env python3
"""The Python binding's overhead: `ontogeny.evaluate_many` on 2 threads against the command
line doing the same evaluations on 2 cores.

Two figures, one run each:

1. like for like: N walker evaluations (in turns of 4) of the bench chain (`benches/chain10.lsys`, the
   10-part chain `ontogeny bench` measures) by `evaluate_many(..., threads=2)`, against the
   same N evaluations by `ontogeny eval benches/chain10.lsys --task walker --json`, two
   processes at a time; the ratio of their evaluations per second is the binding's overhead
   (the command line's figure includes starting a process and growing the chain each time,
   a few milliseconds per evaluation);
2. for reference, `ontogeny bench`'s "all cores" evaluations per second with 2 threads
   (`RAYON_NUM_THREADS=2`): bare controller-on walks of the same seconds, without the
   walker task's settling phases, so more per second than either figure above.

    pip install ./python
    python benches/python_overhead.py [--evaluations 32] [--seconds 20] [--bin target/release/ontogeny]
"""

import argparse
import json
import os
import re
import subprocess
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import ontogeny

ROOT = Path(__file__).resolve().parents[1]
CHAIN = ROOT / "benches" / "chain10.lsys"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--evaluations", type=int, default=32)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--bin", default=str(ROOT / "target" / "release" / "ontogeny"))
    args = parser.parse_args()
    n, seconds = args.evaluations, args.seconds

    chain = ontogeny.load(CHAIN)
    ontogeny.evaluate(chain, "walker", seconds=1)  # warm up
    command = [args.bin, "eval", str(CHAIN), "--task", "walker", "--seconds", str(seconds), "--json"]

    def one(_):
        return json.loads(subprocess.run(command, capture_output=True, text=True, check=True).stdout)

    # The two take turns, a batch of 2 × 2 evaluations each, so that the load of a shared
    # machine weighs on both alike.
    python_time = cli_time = 0.0
    same = True
    with ThreadPoolExecutor(max_workers=2) as pool:
        for _ in range(0, n, 4):
            started = time.perf_counter()
            results = ontogeny.evaluate_many([chain] * 4, "walker", seconds=seconds, threads=2)
            python_time += time.perf_counter() - started
            started = time.perf_counter()
            cli_results = list(pool.map(one, range(4)))
            cli_time += time.perf_counter() - started
            same = same and all(r.fitness == c["fitness"] for r, c in zip(results, cli_results))
    n = 4 * ((n + 3) // 4)
    python_rate, cli_rate = n / python_time, n / cli_time

    bench = subprocess.run(
        [args.bin, "bench", "--evaluations", str(n), "--seconds", str(seconds)],
        capture_output=True, text=True, check=True, env={**os.environ, "RAYON_NUM_THREADS": "2"},
    ).stdout
    all_cores = re.search(r"all cores: ([0-9.]+) evaluations/s", bench)

    print(f"{n} walker evaluations of benches/chain10.lsys, {seconds:g} s each, on 2 threads")
    print(f"  evaluate_many (Python):       {python_rate:8.2f} evaluations/s")
    print(f"  ontogeny eval (2 processes):  {cli_rate:8.2f} evaluations/s")
    print(f"  ratio Python / command line:  {python_rate / cli_rate:8.3f}  (overhead {100 * (1 - python_rate / cli_rate):+.1f}%)")
    print(f"  same fitness as the command line: {'yes' if same else 'NO'}")
    if all_cores:
        print(f"ontogeny bench, all cores (2 threads, bare walks): {float(all_cores.group(1)):.2f} evaluations/s")


if __name__ == "__main__":
    main()
