#!/usr/bin/env bash
# Segmentation gallery of the FAUST poses tr_reg_000..009, like the paper's Figure 3: each shape
# segmented by `specseg segment`, segment colours aligned to tr_reg_000's (FAUST shares vertices, so the
# ground truth is the identity), boundary triangles neutral, centres as black spheres, 5 x 2 panels.
#
#   scripts/faust_gallery.sh [-b SPECSEG] [-d DATA] [-o OUT.png] [-w WORKDIR] [--view V] [--size WxH]
# Defaults: build/specseg, ../shared/data, faust_gallery.png, a temporary work folder (kept with -w).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BIN="$ROOT/build/specseg"
DATA="$ROOT/../shared/data"
OUT="faust_gallery.png"
WORK=""
VIEW="front"
SIZE="360x720"
while [ $# -gt 0 ]; do
  case "$1" in
    -b) BIN=$2; shift 2 ;;
    -d) DATA=$2; shift 2 ;;
    -o) OUT=$2; shift 2 ;;
    -w) WORK=$2; shift 2 ;;
    --view) VIEW=$2; shift 2 ;;
    --size) SIZE=$2; shift 2 ;;
    -h|--help) sed -n '2,8p' "$0"; exit 0 ;;
    *) echo "faust_gallery.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
[ -x "$BIN" ] || { echo "faust_gallery.sh: no specseg binary at $BIN (build first or pass -b)" >&2; exit 1; }
[ -f "$DATA/faust/tr_reg_000.off" ] || { echo "faust_gallery.sh: no FAUST data under $DATA/faust" >&2; exit 1; }
if [ -z "$WORK" ]; then
  WORK=$(mktemp -d)
  trap 'rm -rf "$WORK"' EXIT
else
  mkdir -p "$WORK"
fi

meshes=() labels=() centers=()
for i in 0 1 2 3 4 5 6 7 8 9; do
  name=$(printf "tr_reg_%03d" "$i")
  mesh="$DATA/faust/$name.off"
  "$BIN" segment "$mesh" -o "$WORK/$name.labels.txt" --centers "$WORK/$name.centers.txt"
  meshes+=("$mesh")
  labels+=(--labels "$WORK/$name.labels.txt")
  centers+=(--centers "$WORK/$name.centers.txt")
done
"$BIN" render "${meshes[@]}" "${labels[@]}" "${centers[@]}" --match-colors "$WORK/tr_reg_000.labels.txt" \
  --cols 5 --size "$SIZE" --view "$VIEW" -o "$OUT"
