#!/bin/bash
# Walks each replicate's champion of a comparison (or of evolve runs laid out as
# DIR/ENCODING/rep-N) again, as docs/results/speed.md's "Why the default is physics at 1/240 s"
# does: at its own setting (the stored score), at its own setting with the joint strength
# raised by 0.01%, at the fine reference (4 x 8) and at 16 substeps of 8 iterations.
#   bash benches/rewalk.sh DIR [FLAGS OF ITS OWN SETTING...] > rewalk.csv
# e.g. bash benches/rewalk.sh runs/cmp-walker-fast --setting fast
# Prints CSV: encoding,rep,stored,perturbed,fine,fine16 (walker, distance in metres; an
# exploded walk scores -999999).
ontogeny=${ONTOGENY:-target/release/ontogeny}
dir=$1
shift
fit() {
  "$ontogeny" eval "$1" --task walker --fitness distance "${@:2}" --json 2>/dev/null |
    python3 -c 'import json,sys; print(json.load(sys.stdin)["fitness"])' 2>/dev/null || echo NA
}
echo "encoding,rep,stored,perturbed,fine,fine16"
for enc_dir in "$dir"/*/; do
  enc=$(basename "$enc_dir")
  for rep in $(ls -d "$enc_dir"rep-* 2>/dev/null | sort -V); do
    [ -d "$rep" ] || continue
    f=$(ls "$rep"/best.* 2>/dev/null | head -1)
    [ -n "$f" ] || continue
    echo "$enc,$(basename "$rep"),$(fit "$f" "$@"),$(fit "$f" "$@" --strength 10001),$(fit "$f" --setting fine),$(fit "$f" --substeps 16 --solver-iterations 8 --pgs-iterations 1 --rest-substeps 16 --rest-solver-iterations 8)"
  done
done
