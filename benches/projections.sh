#!/bin/bash
# Projections of the schedule simulator (docs/results/speed.md): from one profile, the share of
# the ceiling that the generational algorithm (walks longest-first) and a steady-state one
# (W births in flight) would reach on other machines and populations, with rank 0 charged
# DRIVER microseconds of serial work per evaluation ("recorded": the profile's own time outside
# evaluation, per evaluation). A benchmark of the simulator, not a test.
#   bash benches/projections.sh [PROFILE] > projections.txt
# PROFILE defaults to docs/compare/schedule/p100.jsonl (the README's evolution, population 100,
# one thread). Each line: population, threads, driver µs, then "generational" or
# "steady-state W" and the share of the ceiling (as many independent one-thread runs of the
# generational algorithm as threads).
ontogeny=${ONTOGENY:-target/release/ontogeny}
profile=${1:-docs/compare/schedule/p100.jsonl}
share() { "$ontogeny" runs schedule "$profile" --json "$@" |
  python3 -c 'import json,sys; j=json.load(sys.stdin); p=j["predictions"][0]; print(round(p["evaluations_per_second"]/j["ceiling_per_thread"]/p["machine"]["threads"], 3))'; }
echo "population threads driver_us schedule share_of_ceiling"
for pop in 100 300 10000; do
  gens=$([ "$pop" -ge 10000 ] && echo 30 || echo 40)
  for threads in 16 64 1024; do
    for us in recorded 40 400; do
      draw=(--population "$pop" --generations "$gens" --threads "$threads")
      [ "$us" != recorded ] && draw+=(--driver-us "$us")
      echo "$pop $threads $us generational $(share "${draw[@]}" --longest-first)"
      for w in $((pop / 2)) "$pop"; do
        echo "$pop $threads $us steady-state-$w $(share "${draw[@]}" --steady-state "$w")"
      done
    done
  done
done
