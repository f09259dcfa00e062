#!/usr/bin/env bash
# Recompute pair means of a `specseg eval --benchmark` run with `specseg error`, independently of the
# run: for each of the first N scored rows of METHOD in OUTDIR/pairs.csv, the K-point files
# MAPK (line k = map[vts_X[k] - 1]) and GTK (vts_Y[k] - 1), K the points both .vts files have, then
# `specseg error MAPK Y --gt GTK`; prints each pair's two means and the largest difference.
#   scripts/benchmark_check.sh SPECSEG BENCHDIR OUTDIR [METHOD [N [MAPDIR]]]
# METHOD default specseg (its maps in OUTDIR/maps), N default 5; MAPDIR: an external method's folder.
set -euo pipefail
BIN=${1:?usage: $0 SPECSEG BENCHDIR OUTDIR [METHOD [N [MAPDIR]]]}
BENCH=${2:?benchmark folder}
OUT=${3:?output folder of the run}
METHOD=${4:-specseg}
N=${5:-5}
MAPS=${6:-$OUT/maps}
MESHES=$BENCH
for s in vtx_5k off shapes; do [ -d "$BENCH/$s" ] && MESHES=$BENCH/$s && break; done
CORRES=$MESHES/corres
[ -d "$CORRES" ] || CORRES=$BENCH/corres
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
grep "^$METHOD," "$OUT/pairs.csv" | grep ',ok,' > "$T/rows" || true
head -n "$N" "$T/rows" | while IFS=, read -r m x y mean rest; do
  nx=$(wc -l < "$CORRES/$x.vts") ny=$(wc -l < "$CORRES/$y.vts")
  K=$((nx < ny ? nx : ny))
  head -n "$K" "$CORRES/$x.vts" | awk 'NR == FNR { m[NR - 1] = $1; next } { print m[$1 - 1] }' "$MAPS/${x}__$y.txt" - > "$T/mk"
  head -n "$K" "$CORRES/$y.vts" | awk '{ print $1 - 1 }' > "$T/gk"
  ymesh=$(ls "$MESHES/$y".* | head -1)
  e=$("$BIN" error "$T/mk" "$ymesh" --gt "$T/gk" --json | grep '"mean_error"' | tr -d ' ,' | cut -d: -f2)
  awk -v a="$mean" -v b="$e" -v x="$x" -v y="$y" 'BEGIN { d = a - b; if (d < 0) d = -d;
    printf "%s -> %s: pairs.csv %.17g, specseg error %.17g, difference %.3g\n", x, y, a, b, d }'
done | tee "$T/report"
awk '{ d = $NF; if (d > w) w = d; n++ } END { printf "%d pairs, largest difference %.3g\n", n, w }' "$T/report"
