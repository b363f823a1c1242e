#!/bin/sh
# The evaluation cache's speed-up on the README's main command: runs
#   ontogeny evolve --config examples/evolve-walker.toml
# twice, one after the other, with the cache (the default) and with --no-cache, and prints
# each wall time, the two final lines (the same best, different simulation counts) and the
# ratio. Run from the repository's root: sh benches/cache.sh
# The runs go to a temporary directory, removed at the end. Other load on the machine
# distorts the times: run it on a quiet machine.
set -eu
cargo build --release --quiet
bin=target/release/ontogeny
work=$(mktemp -d "${TMPDIR:-/tmp}/ontogeny-cache-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT INT TERM

seconds() {
    # Wall seconds of "$@"; its final line (its standard output) goes to standard error.
    start=$(date +%s.%N)
    "$@" >"$work/stdout" 2>"$work/stderr" || { cat "$work/stderr" >&2; exit 1; }
    end=$(date +%s.%N)
    cat "$work/stdout" >&2
    echo "$end - $start" | bc
}

with=$(seconds "$bin" evolve --config examples/evolve-walker.toml --out "$work/with")
without=$(seconds "$bin" evolve --config examples/evolve-walker.toml --out "$work/without" --no-cache)
echo "with the cache:    $with s"
echo "without the cache: $without s"
echo "ratio (without / with): $(echo "scale=2; $without / $with" | bc)"
echo "load average: $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null || echo unknown)"
