#!/usr/bin/env bash
# Whole-process build time: `bodygen lod IN.obj` against bench_meshopt_chain (the
# same OBJ reader, a 10-level meshoptimizer chain, written with its codecs), best
# of N runs each, alternating; prints the ratio (goal <= 1.0). Also peak RSS, and the
# CPU seconds (user + sys, all threads) of each pair with the median per-pair ratio, and
# each binary's process start-up alone (bodygen links DCMTK and assimp for other
# subcommands: their loading is part of every `bodygen lod`; the chain links neither).
# usage: bench/build_vs_meshopt.sh IN.obj [BUILD_DIR=build] [N=3]
set -euo pipefail
in=$1
build=${2:-build}
n=${3:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
best() { sort -g | head -1; }
ours=() base=() pairs=()
for _ in $(seq "$n"); do
  /usr/bin/time -f "%e %M %U %S" -o "$work/t1" "$build/bin/bodygen" lod "$in" -o "$work/out.bpm" >/dev/null
  /usr/bin/time -f "%e %M %U %S" -o "$work/t2" "$build/bin/bench_meshopt_chain" "$in" "$work/out.bin" >/dev/null
  ours+=("$(cat "$work/t1")") base+=("$(cat "$work/t2")")
  # CPU seconds (user + sys) of the pair: on a shared machine wall time is mostly other people's work.
  pairs+=("$(awk '{print $3 + $4}' "$work/t1") $(awk '{print $3 + $4}' "$work/t2")")
done
o=$(printf '%s\n' "${ours[@]}" | cut -d' ' -f1 | best)
b=$(printf '%s\n' "${base[@]}" | cut -d' ' -f1 | best)
orss=$(printf '%s\n' "${ours[@]}" | cut -d' ' -f2 | best)
brss=$(printf '%s\n' "${base[@]}" | cut -d' ' -f2 | best)
echo "$(basename "$in"): bodygen lod ${o} s (${orss} KiB peak), meshopt chain ${b} s (${brss} KiB): ratio $(echo "scale=2; $o / $b" | bc) (goal <= 1.0), best of $n"
med() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
ocpu=$(printf '%s\n' "${pairs[@]}" | cut -d' ' -f1 | med)
bcpu=$(printf '%s\n' "${pairs[@]}" | cut -d' ' -f2 | med)
ratios=$(printf '%s\n' "${pairs[@]}" | awk '{printf "%.3f\n", $1 / $2}' | sort -g)
echo "  CPU (user + sys): bodygen lod ${ocpu} s, meshopt chain ${bcpu} s (medians); per-pair ratio median" \
  "$(echo "$ratios" | med), range $(echo "$ratios" | head -1)-$(echo "$ratios" | tail -1) over $n pairs"
# CPU milliseconds per start (user + sys), over 20 starts that do no work.
startup() {
  local TIMEFORMAT='%3U %3S' t
  t=$({ time (for _ in $(seq 20); do "$@" >/dev/null 2>&1 || true; done); } 2>&1)
  echo "$t" | awk '{printf "%.1f", ($1 + $2) * 1000 / 20}'
}
ostart=$(startup "$build/bin/bodygen" --version)
bstart=$(startup "$build/bin/bench_meshopt_chain")
echo "  start-up alone (CPU per process, 20 starts): bodygen ${ostart} ms, meshopt chain ${bstart} ms;" \
  "the difference is $(echo "scale=1; 100 * ($ostart - $bstart) / ($ocpu * 1000)" | bc) % of bodygen lod's median CPU"
