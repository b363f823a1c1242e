#!/bin/bash
# Walks each replicate's champion of one condition of the growing-while-walking comparison
# again under its condition's configuration: as stored (the default setting), with every
# joint 10% weaker (strength 9000 instead of 10000), and at the fine reference (4 substeps
# of 8 solver iterations). Prints CSV: condition,rep,stored,weaker,fine (distance in metres,
# NA where the walk failed).
#   bash benches/growing-rewalk.sh runs/growing-experiment during examples/growing-experiment-during.toml
ontogeny=${ONTOGENY:-target/release/ontogeny}
dir=$1 condition=$2 config=$3
if grep -q '^\[task\.sim\]' "$config"; then
  echo "growing-rewalk.sh: $config has a [task.sim] table; give one without it" >&2
  exit 2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
variant() { { cat "$config"; printf '\n[task.sim]\n%s\n' "$2"; } > "$tmp/$1.toml"; }
variant stored 'setting = "default"'
variant weaker 'strength = 9000'
variant fine 'setting = "fine"'
walk() {
  "$ontogeny" eval "$2" --config "$tmp/$1.toml" --json 2>/dev/null |
    python3 -c 'import json,sys; print(json.load(sys.stdin)["fitness"])' 2>/dev/null || echo NA
}
echo "condition,rep,stored,weaker,fine"
for rep in $(ls -d "$dir/$condition"/rep-* 2>/dev/null | sort -V); do
  f=$(ls "$rep"/best.* 2>/dev/null | head -1)
  [ -n "$f" ] || continue
  echo "$condition,$(basename "$rep"),$(walk stored "$f"),$(walk weaker "$f"),$(walk fine "$f")"
done
