#!/usr/bin/env bash
# `specseg render` end to end on the demo's synthetic humanoid with labels from `specseg segment`:
# PNG sizes, background, every segment's colour on the body, the head's colour at the top, neutral
# boundary triangles, panels, scalar / map / error modes, and the usage (2) and input (1) errors.
# Pixels are decoded by tests/python/png_check.py (stdlib python3); without python3 those checks SKIP.
# Usage: cli_render.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

demo_outputs "$TMP/demo" "$TMP/demo.out" || bad "demo failed: $(tail -3 "$TMP/demo.out")"
M="$TMP/demo/humanoid_pose0.off"
M2="$TMP/demo/humanoid_pose2.off"
if [ ! -s "$M" ]; then
  skip "the demo wrote no humanoid"
  finish
fi
NV=$(sed -n 2p "$M" | awk '{print $1}')
# the demo's segmentation picture
[ -s "$TMP/demo/humanoid_segments.png" ] && ok || bad "demo wrote no humanoid_segments.png"
grep -q "humanoid_segments.png" "$TMP/demo.out" && ok || bad "demo summary does not list the picture"

"$BIN" segment "$M" -o "$TMP/l.txt" --centers "$TMP/c.txt" --faces 6000 > /dev/null 2>&1 || bad "segment failed"
"$BIN" segment "$M2" -o "$TMP/l2.txt" --faces 6000 > /dev/null 2>&1 || bad "segment pose 2 failed"
NS=$(grep -cv '^#' "$TMP/c.txt")

# ---- segmentation picture ----
if "$BIN" render "$M" --labels "$TMP/l.txt" -o "$TMP/seg.png" --size 300x400 --no-titles > "$TMP/out" 2> "$TMP/err"; then ok
else bad "render --labels: exit $? $(cat "$TMP/err")"; fi
grep -q "rendered in" "$TMP/out" && ok || bad "no timing line: $(cat "$TMP/out")"
head -c 8 "$TMP/seg.png" | od -An -c | grep -q "P   N   G" && ok || bad "not a PNG"
if [ -z "$PY" ]; then
  skip "pixel checks (no python3)"
else
  [ "$(png "$TMP/seg.png" size)" = "300 400" ] && ok || bad "size $(png "$TMP/seg.png" size)"
  [ "$(png "$TMP/seg.png" pixel 0 0)" = "255 255 255" ] && ok || bad "background corner $(png "$TMP/seg.png" pixel 0 0)"
  [ "$(png "$TMP/seg.png" pixel 299 399)" = "255 255 255" ] && ok || bad "background corner 2"
  # every segment's colour shows on the body (front view: all 8 parts of the humanoid face the camera)
  PAL=("230 25 75" "60 180 75" "255 200 25" "0 130 200" "245 130 48" "145 30 180" "70 220 220" "240 50 230"
       "170 110 40" "128 128 0" "0 128 128" "250 170 190")
  seen=0
  for ((s = 0; s < NS && s < 12; s++)); do
    n=$(png "$TMP/seg.png" chroma ${PAL[$s]})
    [ "$n" -ge 20 ] && seen=$((seen + 1))
  done
  [ "$seen" -eq "$NS" ] && ok || bad "only $seen of $NS segment colours visible"
  # boundary triangles in the neutral grey
  g=$(png "$TMP/seg.png" grey)
  [ "$g" -ge 30 ] && ok || bad "neutral boundary pixels: $g"
  # the topmost pixel is the head: its colour is the label of the highest vertex
  read -r TX TY <<< "$(png "$TMP/seg.png" top)"
  HV=$(awk 'NR==2{nv=$1} NR>2 && NR<=2+nv { if (best == "" || $2 > best) { best = $2; bi = NR - 3 } } END { print bi }' "$M")
  HL=$(grep -v '^#' "$TMP/l.txt" | sed -n "$((HV + 1))p")
  read -r R G B <<< "$(png "$TMP/seg.png" pixel "$TX" $((TY + 8)))"
  read -r r g b <<< "${PAL[$HL]}"
  awk -v R="$R" -v G="$G" -v B="$B" -v r="$r" -v g="$g" -v b="$b" \
    'BEGIN { c = (R*r + G*g + B*b) / sqrt((R*R + G*G + B*B) * (r*r + g*g + b*b)); exit !(c > 0.98) }' && ok ||
    bad "head pixel $R $G $B is not segment $HL's colour ($r $g $b)"
fi

# ---- panels, centres, colour alignment ----
"$BIN" render "$M" "$M2" --labels "$TMP/l.txt" --labels "$TMP/l2.txt" --match-colors "$TMP/l.txt" \
  --centers "$TMP/c.txt" --cols 2 --size 200x300 --view 30,10 -o "$TMP/pair.png" > /dev/null 2>&1 && ok || bad "two panels"
[ -z "$PY" ] || { read -r W H <<< "$(png "$TMP/pair.png" size)"; [ "$W" = 400 ] && [ "$H" -gt 300 ] && ok || bad "panel size $W $H"; }

# ---- scalar field with isolines: panel plus colour bar ----
"$BIN" geodesic "$M" --source 0 -o "$TMP/d.txt" > /dev/null 2>&1 || bad "geodesic failed"
"$BIN" render "$M" --scalar "$TMP/d.txt" --isolines 8 --size 200x300 -o "$TMP/sc.png" > /dev/null 2>&1 && ok || bad "scalar"
[ -z "$PY" ] || { read -r W H <<< "$(png "$TMP/sc.png" size)"; [ "$W" -gt 200 ] && ok || bad "no colour bar: width $W"; }

# ---- map (identity: X looks like Y) and error (identity: zero everywhere, no red on the body) ----
seq 0 $((NV - 1)) > "$TMP/id.txt"
"$BIN" render "$M" --map "$TMP/id.txt" --target "$M2" --size 200x300 -o "$TMP/map.png" > /dev/null 2>&1 && ok || bad "map"
[ -z "$PY" ] || { read -r W H <<< "$(png "$TMP/map.png" size)"; [ "$W" = 400 ] && ok || bad "map panels width $W"; }
"$BIN" render "$M" --error "$TMP/id.txt" --target "$M2" --size 200x300 -o "$TMP/err.png" > "$TMP/out" 2>&1 && ok || bad "error: $(cat "$TMP/out")"
if [ -n "$PY" ]; then
  [ "$(png "$TMP/err.png" red 200)" = 0 ] && ok || bad "identity map shows red error on the body"
  [ "$(png "$TMP/err.png" red)" -gt 0 ] && ok || bad "no colour scale drawn"
fi
# a map with errors: red appears on the body
awk '{ print (NR % 3 == 0) ? 0 : $1 }' "$TMP/id.txt" > "$TMP/bad.txt"
"$BIN" render "$M" --error "$TMP/bad.txt" --target "$M" --size 200x300 -o "$TMP/err2.png" > /dev/null 2>&1 && ok || bad "error 2"
[ -z "$PY" ] || { [ "$(png "$TMP/err2.png" red 200)" -gt 50 ] && ok || bad "bad map shows no red"; }

# ---- two-column landmark files ("i j", as `specseg match` takes): column 1 on the first mesh, column 2
# on the second (or on the --target of --map); the same pictures as one-column files per mesh ----
NV2=$(sed -n 2p "$M2" | awk '{print $1}')
printf '# i j\n0 %d\n%d 7\n' $((NV2 - 1)) $((NV / 2)) > "$TMP/lm2.txt"
printf '0\n%d\n' $((NV / 2)) > "$TMP/lma.txt"
printf '%d\n7\n' $((NV2 - 1)) > "$TMP/lmb.txt"
R=(--size 120x160 --no-titles)
"$BIN" render "$M" "$M2" --labels "$TMP/l.txt" --labels "$TMP/l2.txt" --landmarks "$TMP/lm2.txt" "${R[@]}" -o "$TMP/lm2.png" > /dev/null 2>&1 &&
  ok || bad "render with a two-column landmark file"
"$BIN" render "$M" "$M2" --labels "$TMP/l.txt" --labels "$TMP/l2.txt" --landmarks "$TMP/lma.txt" --landmarks "$TMP/lmb.txt" "${R[@]}" -o "$TMP/lmab.png" > /dev/null 2>&1 &&
  ok || bad "render with per-mesh landmark files"
cmp -s "$TMP/lm2.png" "$TMP/lmab.png" && ok || bad "two-column file and per-mesh columns give different pictures"
"$BIN" render "$M" "$M2" --labels "$TMP/l.txt" --labels "$TMP/l2.txt" "${R[@]}" -o "$TMP/nolm.png" > /dev/null 2>&1
cmp -s "$TMP/lm2.png" "$TMP/nolm.png" && bad "landmarks drew nothing" || ok
# one mesh: column 1 only
"$BIN" render "$M" --labels "$TMP/l.txt" --landmarks "$TMP/lm2.txt" "${R[@]}" -o "$TMP/lm1.png" > /dev/null 2>&1 && ok || bad "one mesh, two columns"
"$BIN" render "$M" --labels "$TMP/l.txt" --landmarks "$TMP/lma.txt" "${R[@]}" -o "$TMP/lm1a.png" > /dev/null 2>&1
cmp -s "$TMP/lm1.png" "$TMP/lm1a.png" && ok || bad "one mesh: two-column file is not its first column"
# column 2 out of range: fine for one mesh (unused), an error for two meshes and for a --map target
printf '0 %d\n' "$NV2" > "$TMP/lmbad.txt"
"$BIN" render "$M" --landmarks "$TMP/lmbad.txt" "${R[@]}" -o "$TMP/x.png" > /dev/null 2>&1 && ok || bad "one mesh used column 2"
"$BIN" render "$M" "$M2" --landmarks "$TMP/lmbad.txt" "${R[@]}" -o "$TMP/x.png" > /dev/null 2> "$TMP/e"
[ $? = 1 ] && grep -q "vertex $NV2 out of range" "$TMP/e" && ok || bad "two meshes: column 2 not checked on mesh 2: $(cat "$TMP/e")"
"$BIN" render "$M" --map "$TMP/id.txt" --target "$M2" --landmarks "$TMP/lmbad.txt" "${R[@]}" -o "$TMP/x.png" > /dev/null 2>&1
[ $? = 1 ] && ok || bad "--map: column 2 not used on the target"
"$BIN" render "$M" --map "$TMP/id.txt" --target "$M2" --landmarks "$TMP/lm2.txt" "${R[@]}" -o "$TMP/x.png" > /dev/null 2>&1 &&
  ok || bad "--map with a two-column landmark file"
"$BIN" render "$M" "$M2" "$M" --landmarks "$TMP/lm2.txt" "${R[@]}" -o "$TMP/x.png" > /dev/null 2>&1
[ $? = 2 ] && ok || bad "three meshes with a two-column file: exit != 2"
printf '0 1 2\n' > "$TMP/lm3.txt"
"$BIN" render "$M" --landmarks "$TMP/lm3.txt" "${R[@]}" -o "$TMP/x.png" > /dev/null 2> "$TMP/e"
[ $? = 1 ] && grep -q "lm3.txt:1:" "$TMP/e" && ok || bad "three columns: $(cat "$TMP/e")"

# ---- errors ----
expect() { # expect CODE ARGS...
  local want=$1; shift
  "$BIN" render "$@" > /dev/null 2> "$TMP/e"; local got=$?
  if [ "$got" = "$want" ]; then ok; else bad "render $* -> exit $got, want $want"; fi
  if [ "$want" = 1 ]; then grep -q "^specseg: error: " "$TMP/e" && ok || bad "no 'specseg: error:' for: render $*"; fi
}
head -n 10 "$TMP/l.txt" > "$TMP/short.txt"
expect 1 "$M" --labels "$TMP/short.txt" -o "$TMP/x.png"
expect 1 "$TMP/missing.off" -o "$TMP/x.png"
echo "$NV" > "$TMP/oob.txt"; seq 1 $((NV - 1)) >> "$TMP/oob.txt"
expect 1 "$M" --map "$TMP/oob.txt" --target "$M2" -o "$TMP/x.png"
expect 1 "$M" -o "$TMP/no-such-dir/x.png"
expect 2 "$M"
expect 2 -o "$TMP/x.png"
expect 2 "$M" --size 5x5 -o "$TMP/x.png"
expect 2 "$M" --view sideways -o "$TMP/x.png"
expect 2 "$M" --map "$TMP/id.txt" -o "$TMP/x.png"
expect 2 "$M" --labels "$TMP/l.txt" --scalar "$TMP/d.txt" -o "$TMP/x.png"
expect 2 "$M" "$M2" --labels "$TMP/l.txt" --labels "$TMP/l.txt" --labels "$TMP/l.txt" -o "$TMP/x.png"
expect 2 "$M" --bogus -o "$TMP/x.png"
"$BIN" render --help > /dev/null && ok || bad "--help"

finish
