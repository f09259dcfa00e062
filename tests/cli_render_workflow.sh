#!/usr/bin/env bash
# `specseg render` on one's own meshes: --up (and the automatic axis: a z-up TOSCA shape stands upright,
# its silhouette taller than wide from the front and its highest vertex at the top of the picture),
# --scale fit|common, a PLY's own vertex colours (a segmented PLY re-rendered keeps its colours), the
# checker texture of --map, and the usage errors of the new options. The TOSCA checks SKIP (exit 77)
# without the data; pixel checks need python3 (tests/python/png_check.py).
# Usage: cli_render_workflow.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
DATA=${SS_DATA_DIR:-$(dirname "$0")/../../shared/data}

demo_outputs "$TMP/demo" "$TMP/demo.out" || bad "demo failed: $(tail -3 "$TMP/demo.out")"
M="$TMP/demo/humanoid_pose0.off"
[ -s "$M" ] || { bad "the demo wrote no humanoid"; finish; }
if [ -z "$PY" ]; then
  skip "pixel checks (no python3)"
  finish
fi
# a panel's silhouette: "W H" of the non-white pixels in columns [X0, X1)
sil() { read -r a b c d <<< "$(png "$1" bbox "$2" "$3")"; echo $((c - a + 1)) $((d - b + 1)); }
R=(--size 200x200 --no-titles)

# ---- --up on a y-up mesh turned z-up (awk: (x, y, z) -> (x, -z, y)) ----
awk -v OFMT=%.17g 'NR == 2 { nv = $1 } NR > 2 && NR <= 2 + nv { print $1, -$3, $2; next } { print }' "$M" > "$TMP/z.off"
"$BIN" render "$M" --up y "${R[@]}" -o "$TMP/y.png" > "$TMP/out" 2>&1 && ok || bad "render --up y: $(cat "$TMP/out")"
grep -q "up +y" "$TMP/out" && ok || bad "summary does not name the up axis: $(cat "$TMP/out")"
"$BIN" render "$TMP/z.off" --up=z "${R[@]}" -o "$TMP/z.png" > /dev/null 2>&1 && ok || bad "render --up=z"
cmp -s "$TMP/y.png" "$TMP/z.png" && ok || bad "the z-up copy drawn with --up z differs from the y-up original"
"$BIN" render "$TMP/z.off" --up y "${R[@]}" -o "$TMP/zy.png" > /dev/null 2>&1
cmp -s "$TMP/y.png" "$TMP/zy.png" && bad "--up y and --up z give the same picture of the z-up copy" || ok
# the automatic axis finds both
"$BIN" render "$TMP/z.off" "${R[@]}" -o "$TMP/za.png" > "$TMP/out" 2>&1
grep -q "up +z" "$TMP/out" && cmp -s "$TMP/za.png" "$TMP/y.png" && ok || bad "auto on the z-up copy: $(cat "$TMP/out")"
"$BIN" render "$M" "${R[@]}" -o "$TMP/ya.png" > "$TMP/out" 2>&1
grep -q "up +y" "$TMP/out" && cmp -s "$TMP/ya.png" "$TMP/y.png" && ok || bad "auto on the y-up humanoid: $(cat "$TMP/out")"
# upside down: the highest vertex (z field: yellow at the top of viridis) is at the bottom of the picture
awk 'NR == 2 { nv = $1 } NR > 2 && NR <= 2 + nv { print $2 }' "$M" > "$TMP/h.txt"
top_colour() { read -r TX TY <<< "$(png "$1" top)"; png "$1" pixel "$TX" $((TY + 2)); }
"$BIN" render "$M" --scalar "$TMP/h.txt" --up=-y "${R[@]}" -o "$TMP/down.png" > /dev/null 2>&1 && ok || bad "--up=-y"
"$BIN" render "$M" --scalar "$TMP/h.txt" "${R[@]}" -o "$TMP/upright.png" > /dev/null 2>&1 && ok || bad "--scalar"
read -r r g b <<< "$(top_colour "$TMP/upright.png")"
[ "$r" -gt 150 ] && [ "$g" -gt 150 ] && [ "$b" -lt 120 ] && ok || bad "upright: top pixel $r $g $b is not the high (yellow) end"
read -r r g b <<< "$(top_colour "$TMP/down.png")"
[ "$r" -lt 120 ] && [ "$b" -gt "$g" ] && ok || bad "--up=-y: top pixel $r $g $b is not the low (dark blue) end"

# ---- --scale: a copy at 0.4 times the size is drawn as large (fit, the default) or smaller (common) ----
awk 'NR == 2 { nv = $1 } NR > 2 && NR <= 2 + nv { print 0.4 * $1, 0.4 * $2, 0.4 * $3; next } { print }' "$M" > "$TMP/small.off"
"$BIN" render "$M" "$TMP/small.off" "${R[@]}" -o "$TMP/fit.png" > /dev/null 2>&1 && ok || bad "two panels, fit"
"$BIN" render "$M" "$TMP/small.off" --scale common "${R[@]}" -o "$TMP/common.png" > /dev/null 2>&1 && ok || bad "--scale common"
"$BIN" render "$M" "$TMP/small.off" --scale=fit "${R[@]}" -o "$TMP/fit2.png" > /dev/null 2>&1 && ok || bad "--scale=fit"
cmp -s "$TMP/fit.png" "$TMP/fit2.png" && ok || bad "fit is not the default without --map / --error"
read -r w1 h1 <<< "$(sil "$TMP/fit.png" 0 200)"
read -r w2 h2 <<< "$(sil "$TMP/fit.png" 200 400)"
[ $((h1 - h2)) -le 3 ] && [ $((h2 - h1)) -le 3 ] && ok || bad "fit: panel heights $h1 and $h2 differ"
read -r w2 h2 <<< "$(sil "$TMP/common.png" 200 400)"
[ "$h2" -lt $((h1 / 2)) ] && ok || bad "common: the small copy is $h2 px high, the original $h1"

# ---- a PLY's own colours: a segmented PLY re-rendered shows its segment colours ----
"$BIN" segment "$M" -o "$TMP/l.txt" --ply "$TMP/seg.ply" --faces 6000 > /dev/null 2>&1 || bad "segment --ply failed"
# the PLY carries the labels as an int vertex property 'label' beside the colours
"$PY" - "$TMP/seg.ply" "$TMP/l.txt" <<'PYEOF' && ok || bad "segment --ply: no 'label' property equal to the labels"
import struct, sys
data = open(sys.argv[1], "rb").read()
head, body = data.split(b"end_header\n", 1)
assert b"property uchar blue\nproperty int label\n" in head, head
nv = int(head.split(b"element vertex ")[1].split()[0])
lab = [struct.unpack_from("<i", body, 31 * i + 27)[0] for i in range(nv)]
want = [int(x) for x in open(sys.argv[2]) if x.strip() and not x.startswith("#")]
assert lab == want, (lab[:10], want[:10])
PYEOF
"$BIN" render "$TMP/seg.ply" "${R[@]}" -o "$TMP/ply.png" > /dev/null 2>&1 && ok || bad "render a coloured PLY"
"$BIN" render "$M" "${R[@]}" -o "$TMP/plain.png" > /dev/null 2>&1 || bad "render the OFF"
PAL=("230 25 75" "60 180 75" "255 200 25" "0 130 200" "245 130 48" "145 30 180")
seen=0
for c in "${PAL[@]}"; do
  [ "$(png "$TMP/ply.png" chroma $c)" -ge 20 ] && seen=$((seen + 1))
  [ "$(png "$TMP/plain.png" chroma $c)" -eq 0 ] || bad "the plain OFF shows colour $c"
done
[ "$seen" -ge 5 ] && ok || bad "the re-rendered PLY shows $seen of 6 segment colours"
# ... and from standard input too
"$BIN" render - "${R[@]}" -o "$TMP/ply_stdin.png" < "$TMP/seg.ply" > /dev/null 2>&1
cmp -s "$TMP/ply.png" "$TMP/ply_stdin.png" && ok || bad "the coloured PLY through stdin draws differently"
# a colouring option wins over the file's colours
"$BIN" render "$TMP/seg.ply" --scalar "$TMP/h.txt" "${R[@]}" -o "$TMP/ply_sc.png" > /dev/null 2>&1 && ok || bad "PLY + --scalar"
[ "$(png "$TMP/ply_sc.png" chroma 230 25 75 200)" -lt 20 ] && ok || bad "--scalar did not replace the PLY's colours"

# ---- --map: the target carries the checker texture (a flat grid facing the camera: brightness drops
# along a row only where the checker darkens a cell; plain coordinate colours would only rise) ----
# (at z = 0.3: the checker is a product of sines, zero on the plane z = 0)
awk 'BEGIN { n = 101; print "OFF"; print n * n, 2 * (n - 1) * (n - 1), 0
  for (j = 0; j < n; j++) for (i = 0; i < n; i++) print i / (n - 1), j / (n - 1), 0.3
  for (j = 0; j < n - 1; j++) for (i = 0; i < n - 1; i++) { a = j * n + i; print 3, a, a + 1, a + n + 1; print 3, a, a + n + 1, a + n } }' > "$TMP/grid.off"
seq 0 $((101 * 101 - 1)) > "$TMP/gid.txt"
"$BIN" render "$TMP/grid.off" --map "$TMP/gid.txt" --target "$TMP/grid.off" --up y "${R[@]}" -o "$TMP/map.png" > /dev/null 2>&1 &&
  ok || bad "render --map on the grid"
drops=$(png "$TMP/map.png" row 100 20 180 | awk '{ d = 0; for (i = 3; i <= NF; i++) if ($i < $(i - 2) - 20) d++; print d }')
[ "$drops" -ge 5 ] && ok || bad "no checker on the --map target: $drops brightness drops along a row"

# ---- OBJ output: a mesh written as .obj reads back with the same counts ----
"$BIN" smooth "$M" --steps 1 -o "$TMP/s.obj" > /dev/null 2>&1 && ok || bad "smooth -o S.obj"
head -1 "$TMP/s.obj" | grep -q "^# written by specseg" && grep -q "^f 1 \|^f [0-9]* [0-9]* [0-9]*$" "$TMP/s.obj" && ok || bad "not an OBJ"
"$BIN" info "$TMP/s.obj" > "$TMP/i1" 2>&1
"$BIN" info "$M" > "$TMP/i2" 2>&1
c1=$(grep -E '^(vertices|faces):' "$TMP/i1"); c2=$(grep -E '^(vertices|faces):' "$TMP/i2")
[ -n "$c1" ] && [ "$c1" = "$c2" ] && ok || bad "OBJ counts differ: $c1 / $c2"

# ---- usage errors ----
for a in "--up w" "--up=" "--scale big" "--scale"; do
  # shellcheck disable=SC2086
  "$BIN" render "$M" $a -o "$TMP/x.png" > /dev/null 2>&1
  [ $? = 2 ] && ok || bad "render $a: exit != 2"
done
"$BIN" render --help | grep -q -- "--up AXIS" && ok || bad "--help does not list --up"

# ---- TOSCA (z-up): upright by default, taller than wide from the front, the head at the top ----
T="$DATA/tosca/victoria0.off"
if [ ! -s "$T" ]; then
  skip "TOSCA absent ($T): the z-up picture test"
  finish
fi
"$BIN" render "$T" "${R[@]}" -o "$TMP/t.png" > "$TMP/out" 2>&1 && ok || bad "render TOSCA: $(cat "$TMP/out")"
grep -q "up +z" "$TMP/out" && ok || bad "TOSCA: $(cat "$TMP/out")"
read -r w h <<< "$(sil "$TMP/t.png" 0 200)"
[ "$h" -gt "$w" ] && ok || bad "TOSCA victoria0 is $w px wide, $h px high (not upright)"
"$BIN" render "$T" --up y "${R[@]}" -o "$TMP/ty.png" > /dev/null 2>&1
read -r w h <<< "$(sil "$TMP/ty.png" 0 200)"
[ "$h" -lt "$w" ] && ok || bad "with --up y, victoria0 should lie ($w x $h)"
awk 'NR == 1 && /OFF/ { next } !nv { nv = $1; next } nv && c < nv { print $3; c++ }' "$T" > "$TMP/tz.txt"
[ "$(wc -l < "$TMP/tz.txt")" -gt 1000 ] || bad "could not read victoria0's z coordinates"
"$BIN" render "$T" --scalar "$TMP/tz.txt" "${R[@]}" -o "$TMP/tz.png" > /dev/null 2>&1 && ok || bad "TOSCA --scalar z"
read -r r g b <<< "$(top_colour "$TMP/tz.png")"
[ "$r" -gt 150 ] && [ "$g" -gt 150 ] && [ "$b" -lt 120 ] && ok || bad "TOSCA: top pixel $r $g $b is not the highest z"
finish
