#!/bin/sh
# Derivations cut short where their result is decided, timed: the wall seconds of each case
# of a runaway derivation, each of which would run for minutes derived step by step.
#   - one part a step (axiom A, A --> forward(0.1) A, a million steps): grow, eval and
#     derive --last; grow and eval stop at the part limit (step 201), derive at the work
#     budget (an error, exit 2, expected);
#   - a fixed point (A --> A, a billion steps): derive --last and grow stop at step 1.
# Run from the repository's root: sh benches/cut_short.sh
set -eu
cargo build --release --quiet
bin=target/release/ontogeny
work=$(mktemp -d "${TMPDIR:-/tmp}/ontogeny-cut-short.XXXXXX")
trap 'rm -rf "$work"' EXIT INT TERM
printf 'axiom: A\nderivation length: 1000000\nA --> forward(0.1) A\n' >"$work/line.lsys"
printf 'axiom: A\nderivation length: 1000000000\nA --> A\n' >"$work/still.lsys"

time_of() {
    # "CASE: S s (exit N)" for the command "$@".
    label=$1
    shift
    start=$(date +%s.%N)
    code=0
    "$@" >/dev/null 2>&1 || code=$?
    end=$(date +%s.%N)
    echo "$label: $(echo "$end - $start" | bc) s (exit $code)"
}

time_of "one part a step, grow" "$bin" grow "$work/line.lsys"
time_of "one part a step, eval" "$bin" eval "$work/line.lsys" --task walker
time_of "one part a step, derive --last" "$bin" derive "$work/line.lsys" --last
time_of "fixed point, derive --last" "$bin" derive "$work/still.lsys" --last
time_of "fixed point, grow" "$bin" grow "$work/still.lsys"
echo "load average: $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null || echo unknown)"
