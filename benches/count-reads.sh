#!/bin/bash
# Counts, in each champion genome given, the lines outside comments that hold an environment
# read (`?E`) and those that hold a chemical neuron (`chem` sensor or `secrete` effector), as
# the Plasticity results page does: "carrying a read" is a count above 0.
#   bash benches/count-reads.sh docs/compare/cyclomorphosis/genomes/*.lsys
echo "genome,read_lines,chemical_lines"
for f in "$@"; do
  echo "$(basename "$f" .lsys),$(grep -v '^#' "$f" | grep -c '?E'),$(grep -v '^#' "$f" | grep -c 'chem\|secrete')"
done
