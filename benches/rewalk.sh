#!/bin/bash
# Walks each replicate's champion of a comparison (or of evolve runs laid out as
# DIR/ENCODING/rep-N) again, as docs/results/speed.md's "Why the default is physics at 1/240 s"
# does: at its own setting (the stored score), at its own setting with the joint strength
# raised by 0.01%, at the fine reference (4 x 8) and at 16 substeps of 8 iterations.
#   bash benches/rewalk.sh DIR [FLAGS OF ITS OWN SETTING...] > rewalk.csv
# e.g. bash benches/rewalk.sh runs/cmp-walker-fast --setting fast
# Prints CSV: encoding,rep,stored,perturbed,fine,fine16 (walker, distance in metres; an
# exploded walk scores -999999).
# A champion file repeats the evaluation it records (its world, habitats and trials). With
# CONFIG=FILE (a run configuration without a [task.sim] table) every walk takes its task from
# FILE's [task] table instead, e.g. the README's walker on flat ground for champions evolved
# on rough ground; "stored" is then the walk at the default setting, and no flags are taken.
#   CONFIG=examples/robust-baseline.toml bash benches/rewalk.sh runs/robust > rewalk-flat.csv
# STRENGTH=S sets the perturbed walk's joint strength (default 10001, the default 10000 raised
# by 0.01%); CONDITION=NAME walks only that condition's (or encoding's) champions, e.g. each
# condition of the growing-while-walking comparison under its own configuration, its joints
# 10% weaker:
#   CONFIG=examples/growing-experiment-during.toml CONDITION=during STRENGTH=9000 \
#     bash benches/rewalk.sh runs/growing-experiment > rewalk-during.csv
ontogeny=${ONTOGENY:-target/release/ontogeny}
dir=$1
shift
fine16=(--substeps 16 --solver-iterations 8 --pgs-iterations 1 --rest-substeps 16 --rest-solver-iterations 8)
# walk KIND FILE: the champion FILE's fitness at KIND (stored, perturbed, fine or fine16).
walk() {
  local flags task=(--task walker --fitness distance)
  case $1 in
    stored) flags=("${own[@]}") ;;
    perturbed) flags=("${own[@]}" --strength "$strength") ;;
    fine) flags=(--setting fine) ;;
    fine16) flags=("${fine16[@]}") ;;
  esac
  if [ -n "$CONFIG" ]; then task=(--config "$tmp/$1.toml") flags=(); fi
  "$ontogeny" eval "$2" "${task[@]}" "${flags[@]}" --json 2>/dev/null |
    python3 -c 'import json,sys; print(json.load(sys.stdin)["fitness"])' 2>/dev/null || echo NA
}
own=("$@")
strength=${STRENGTH:-10001}
if [ -n "$CONFIG" ]; then
  if grep -q '^\[task\.sim\]' "$CONFIG"; then
    echo "rewalk.sh: $CONFIG has a [task.sim] table; give one without it" >&2
    exit 2
  fi
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  # A copy of CONFIG with a [task.sim] table of the walk's settings.
  variant() { { cat "$CONFIG"; printf '\n[task.sim]\n%s\n' "$2"; } > "$tmp/$1.toml"; }
  variant stored 'setting = "default"'
  variant perturbed "strength = $strength"
  variant fine 'setting = "fine"'
  variant fine16 "$(printf 'substeps = 16\nsolver_iterations = 8\npgs_iterations = 1\nrest_substeps = 16\nrest_solver_iterations = 8')"
fi
echo "encoding,rep,stored,perturbed,fine,fine16"
for enc_dir in "$dir"/*/; do
  enc=$(basename "$enc_dir")
  [ -z "$CONDITION" ] || [ "$enc" = "$CONDITION" ] || continue
  for rep in $(ls -d "$enc_dir"rep-* 2>/dev/null | sort -V); do
    [ -d "$rep" ] || continue
    f=$(ls "$rep"/best.* 2>/dev/null | head -1)
    [ -n "$f" ] || continue
    echo "$enc,$(basename "$rep"),$(walk stored "$f"),$(walk perturbed "$f"),$(walk fine "$f"),$(walk fine16 "$f")"
  done
done
