#!/usr/bin/env bash
# What the refined default of `specseg match` costs on top of the paper's unrefined DIFF (issue 12:
# goal <= 0.5 s CPU per FAUST pair): whole commands from two mesh files, one thread, the two variants
# interleaved round by round; prints per pair the median CPU (user + sys) of each and the difference.
#   scripts/bench_refine_cost.sh [BUILD_DIR] [ROUNDS] [PAIRS...]   (defaults: build 5 000,011 020,037 054,068)
# Needs ../shared/data/faust (skips with a message otherwise). Time it alone: CPU time is inflated too
# when other jobs share the cores.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
rounds=${2:-5}
shift 2 2>/dev/null || shift $#
pairs=("$@")
[ ${#pairs[@]} -gt 0 ] || pairs=(000,011 020,037 054,068)
data=${SS_DATA_DIR:-../shared/data}/faust
if [ ! -f "$data/landmarks_best.txt" ]; then
  echo "bench_refine_cost: SKIP: no FAUST data at $data" >&2
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cpu() { # the command's user + sys seconds
  /usr/bin/time -f "%U %S" -o "$tmp/t" env OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 "$@" >/dev/null 2>&1
  awk '{printf "%.3f\n", $1 + $2}' "$tmp/t"
}
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
printf '%-9s %12s %12s %10s\n' pair no-refine refined extra
all=()
for p in "${pairs[@]}"; do
  x=${p%,*} y=${p#*,}
  X="$data/tr_reg_$x.off" Y="$data/tr_reg_$y.off"
  : > "$tmp/a"; : > "$tmp/b"
  for ((r = 0; r < rounds; r++)); do
    cpu "$build/specseg" match "$X" "$Y" --landmarks "$data/landmarks_best.txt" -o "$tmp/m" --no-refine >> "$tmp/a"
    cpu "$build/specseg" match "$X" "$Y" --landmarks "$data/landmarks_best.txt" -o "$tmp/m" >> "$tmp/b"
  done
  a=$(median < "$tmp/a") b=$(median < "$tmp/b")
  d=$(awk -v a="$a" -v b="$b" 'BEGIN {printf "%+.3f", b - a}')
  all+=("$d")
  printf '%-9s %10.3f s %10.3f s %8s s\n' "$x-$y" "$a" "$b" "$d"
done
printf '%s\n' "${all[@]}" | median | awk '{printf "median extra CPU of the refined default: %+.3f s (goal <= 0.5 s)\n", $1}'
