#!/bin/sh
# One population over MPI ranks against one process: a generation of 200 walkers (the README's
# walker run, examples/evolve-walker.toml, with --pop 200 --gens 1) evaluated
#   (a) by one process with 2 threads:      ontogeny evolve ... --threads 2
#   (b) by 2 MPI ranks with 1 thread each:  mpirun -np 2 ontogeny evolve ... --threads 1
#   (c) by 3 MPI ranks with 1 thread each:  mpirun -np 3 ontogeny evolve ... --threads 1
# each ROUNDS times (default 2), in turn, so that other load on the machine falls on all
# alike. Prints every wall time, the efficiency of the 2-rank run (time of (a) / time of (b),
# best of each; 1 is perfect) and, from ONTOGENY_MPI_TIMING, each MPI run's line: how the
# evaluations and births were shared and the CPU time rank 0's main thread used per
# evaluation (CPU time, not wall time: the ranks share the cores), then the load average.
# GENS (default 1) sets the generations and EXTRA adds flags to every run: a steady-state run,
# say, GENS=4 EXTRA="--algorithm steady-state --in-flight 50" sh benches/mpi.sh 1
# Needs Open MPI (mpirun) and the build with the feature. Run from the repository's root:
#   sh benches/mpi.sh [ROUNDS]
# The runs go to a temporary directory, removed at the end.
set -eu
rounds=${1:-2}
cargo build --release --quiet --features mpi
bin=target/release/ontogeny
work=$(mktemp -d "${TMPDIR:-/tmp}/ontogeny-mpi-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT INT TERM
# Open MPI refuses root unless told; this machine alone, waiting ranks yield their core, ranks
# not bound to a core (as the single process is not: other load moves them both alike).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun="mpirun --oversubscribe --bind-to none --mca mpi_yield_when_idle 1"
run="evolve --config examples/evolve-walker.toml --pop 200 --gens ${GENS:-1} ${EXTRA:-}"

seconds() {
    # Wall seconds of "$@"; its final line (standard output) and the MPI line go to standard
    # error.
    start=$(date +%s.%N)
    "$@" >"$work/stdout" 2>"$work/stderr" || { cat "$work/stderr" >&2; exit 1; }
    end=$(date +%s.%N)
    cat "$work/stdout" >&2
    grep '^MPI:' "$work/stderr" >&2 || true
    echo "$end - $start" | bc
}

best_one=
best_mpi=
i=1
while [ "$i" -le "$rounds" ]; do
    one=$(seconds $bin $run --threads 2 --out "$work/one-$i")
    mpi=$(ONTOGENY_MPI_TIMING=1 seconds $mpirun -np 2 $bin $run --threads 1 --out "$work/mpi-$i")
    three=$(ONTOGENY_MPI_TIMING=1 seconds $mpirun -np 3 $bin $run --threads 1 --out "$work/three-$i")
    echo "round $i: 1 process x 2 threads: $one s; 2 ranks x 1 thread: $mpi s; 3 ranks x 1 thread: $three s"
    if [ -z "$best_one" ] || [ "$(echo "$one < $best_one" | bc)" = 1 ]; then best_one=$one; fi
    if [ -z "$best_mpi" ] || [ "$(echo "$mpi < $best_mpi" | bc)" = 1 ]; then best_mpi=$mpi; fi
    i=$((i + 1))
done
echo "best: 1 process x 2 threads: $best_one s; 2 ranks x 1 thread: $best_mpi s"
echo "efficiency of the MPI run: $(echo "scale=3; $best_one / $best_mpi" | bc)"
echo "load average: $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null || echo unknown)"
