#!/bin/bash
# How one evolution fills a machine's cores: for N = 1, 2, 4, ... up to the cores present
# (nproc, which ends the list when it is no power of two), the ceiling — N one-thread runs at
# once, each the same run — against one run with --threads N, at population 100 and 400. The
# run is the README's evolution (examples/evolve-walker.toml: the lsystem genome, Chaumont's
# schedule, 20-second walks, fitness distance) with --no-cache, for GENS generations.
# Prints a table: evaluations per second of the ceiling (all N runs together) and of the one
# run, and their ratio (1 is a run that fills N cores as N separate runs do). Every speed is
# evaluations / wall-clock seconds of the processes, start-up and writing included.
#
# A benchmark, not a test: it needs only the release binary (no cargo, no repository):
#   bash benches/scaling.sh
#   ONTOGENY=/path/to/ontogeny GENS=10 POPS="100 400" bash benches/scaling.sh
# Settings (environment):
#   ONTOGENY  the binary (default target/release/ontogeny)
#   GENS      generations per run (default 10: on 16 cores about 5 minutes for population 100
#             in all, and four times as long for 400)
#   POPS      the populations (default "100 400")
#   THREADS   the thread counts (default 1 2 4 ... up to nproc)
#   PROFILES  a directory to keep each N-thread run's profile in (evolve --profile), as
#             PROFILES/pop-P-threads-N.jsonl, for `ontogeny runs schedule`
#   STEADY    births in flight W of steady-state runs to measure beside the generational one
#             (default none), e.g. STEADY="32 100": for each N, one run with --threads N
#             --algorithm steady-state --in-flight W, as many evaluations (a block of births
#             a generation), against its own ceiling (N one-thread runs of that steady-state
#             run at once: it makes other creatures than the generational run, so only its
#             own one-thread runs do the same work); profiles as
#             PROFILES/pop-P-threads-N-steady-W.jsonl
# The runs go to a temporary directory, removed at the end.
set -eu
ontogeny=${ONTOGENY:-target/release/ontogeny}
gens=${GENS:-10}
pops=${POPS:-100 400}
cores=$(nproc)
if [ -z "${THREADS:-}" ]; then
    THREADS=
    n=1
    while [ "$n" -lt "$cores" ]; do
        THREADS="$THREADS $n"
        n=$((n * 2))
    done
    THREADS="$THREADS $cores"
fi
if ! "$ontogeny" --version >/dev/null 2>&1; then
    echo "error: $ontogeny does not run: build it (cargo build --release) or set ONTOGENY" >&2
    exit 2
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/ontogeny-scaling.XXXXXX")
trap 'rm -rf "$work"' EXIT INT TERM
# The README's evolution, examples/evolve-walker.toml, as it ships.
cat >"$work/walker.toml" <<'TOML'
encoding = "lsystem"
seed = 1

[ga]
preset = "chaumont"
population = 100
generations = 40

[task]
task = "walker"

[task.walker]
seconds = 20
fitness = "distance"
TOML

now() { date +%s.%N; }

# evaluations OUT: the evaluations the run's --json final line in OUT counts.
evaluations() {
    sed -n 's/^  "evaluations": \([0-9]*\),$/\1/p' "$1"
}

# evolve NAME POP THREADS [FLAGS...]: one run into $work/NAME, its final line to NAME.json.
evolve() {
    local name=$1 pop=$2 threads=$3
    shift 3
    "$ontogeny" evolve --config "$work/walker.toml" --no-cache --pop "$pop" --gens "$gens" \
        --threads "$threads" --json --out "$work/$name" "$@" \
        >"$work/$name.json" 2>"$work/$name.err" || {
        cat "$work/$name.err" >&2
        exit 1
    }
}

echo "# $("$ontogeny" --version), $cores cores ($(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -1)), $(date -u +%Y-%m-%dT%H:%MZ)"
echo "# evolve --config examples/evolve-walker.toml --no-cache --pop P --gens $gens; load average before: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
printf '%-10s %7s %-22s %15s %15s %6s\n' population threads algorithm "ceiling eval/s" "one run eval/s" ratio
# ceiling POP N NAME [FLAGS...]: N one-thread runs of the same run at once; prints their
# evaluations per second together.
ceiling() {
    local pop=$1 n=$2 name=$3 start end total pids i
    shift 3
    start=$(now)
    pids=
    for i in $(seq 1 "$n"); do
        evolve "ceiling-$name-$i" "$pop" 1 "$@" &
        pids="$pids $!"
    done
    for pid in $pids; do
        wait "$pid"
    done
    end=$(now)
    total=0
    for i in $(seq 1 "$n"); do
        total=$((total + $(evaluations "$work/ceiling-$name-$i.json")))
    done
    awk -v e="$total" -v s="$start" -v t="$end" 'BEGIN { printf "%.1f", e / (t - s) }'
}
for pop in $pops; do
    for n in $THREADS; do
        # One run with N threads against its ceiling: generational, then steady-state at each
        # W of STEADY. A steady-state run makes other creatures than the generational one (its
        # walks may be cheaper or dearer), so its ceiling is N one-thread runs of itself: its
        # results do not depend on the threads, so they do the same work.
        for algorithm in generational ${STEADY:-}; do
            flags=()
            name="run-$pop-$n"
            label=generational
            if [ "$algorithm" != generational ]; then
                flags=(--algorithm steady-state --in-flight "$algorithm")
                name="run-$pop-$n-steady-$algorithm"
                label="steady-state W=$algorithm"
            fi
            top=$(ceiling "$pop" "$n" "${name#run-}" ${flags[@]+"${flags[@]}"})
            if [ -n "${PROFILES:-}" ]; then
                mkdir -p "$PROFILES"
                flags+=(--profile "$PROFILES/pop-$pop-threads-$n${name#run-"$pop"-"$n"}.jsonl")
            fi
            start=$(now)
            evolve "$name" "$pop" "$n" ${flags[@]+"${flags[@]}"}
            end=$(now)
            one=$(awk -v e="$(evaluations "$work/$name.json")" -v s="$start" -v t="$end" \
                'BEGIN { printf "%.1f", e / (t - s) }')
            ratio=$(awk -v a="$one" -v b="$top" 'BEGIN { printf "%.2f", a / b }')
            printf '%-10s %7s %-22s %15s %15s %6s\n' "$pop" "$n" "$label" "$top" "$one" "$ratio"
            rm -rf "$work"/ceiling-* "$work"/run-*
        done
    done
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
