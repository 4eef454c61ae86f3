#!/usr/bin/env bash
# `bodygen exhibit` on an atlas vs the same work run step by step by hand
# (`build -o DIR/` then one `lod` per OBJ), same options, --jobs 2, interleaved
# runs; prints each wall time and the median ratio. Also the bundle's size.
#   bench/exhibit_vs_steps.sh [BODYGEN] [ATLAS] [RUNS]
set -euo pipefail
BODYGEN=${1:-build/bin/bodygen}
ATLAS=${2:-/usr/share/mricron/templates/aal.nii.gz}
RUNS=${3:-3}
OPTS=(--min-area 3 --smooth 10 --jobs 2)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
ex=() st=()
for r in $(seq "$RUNS"); do
  t0=$(now)
  "$BODYGEN" exhibit "$ATLAS" "${OPTS[@]}" --quiet -o "$tmp/bundle"
  t1=$(now)
  rm -rf "$tmp/objs"
  "$BODYGEN" build "$ATLAS" "${OPTS[@]}" --quiet -o "$tmp/objs/"
  for f in "$tmp"/objs/*.obj; do "$BODYGEN" lod "$f" -o "${f%.obj}.bpm" --jobs 2 --quiet; done
  t2=$(now)
  ex+=("$(echo "$t1 - $t0" | bc)") st+=("$(echo "$t2 - $t1" | bc)")
  echo "run $r: exhibit ${ex[-1]} s, build + lod by hand ${st[-1]} s"
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
me=$(median "${ex[@]}") ms=$(median "${st[@]}")
echo "median: exhibit $me s, by hand $ms s, ratio $(echo "scale=3; $me / $ms" | bc)"
echo "bundle: $(du -sb "$tmp/bundle" | cut -f1) bytes, $(ls "$tmp"/bundle/models | wc -l) models"
