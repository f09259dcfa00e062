#!/usr/bin/env bash
# `specseg demo` end to end: writes its shapes into a new (nested) folder, the files read back with
# `specseg info` as closed manifolds of the right genus, the output names them, its two pictures
# (segment gallery, Figure 9 of the humanoid pair) have the layout's size, usage/IO errors.
# Usage: cli_demo.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

OUT="$TMP/a/b/demo"
if "$BIN" demo -o "$OUT" > "$TMP/out" 2> "$TMP/err"; then ok; else bad "demo exit $? ($(cat "$TMP/err"))"; fi
for s in humanoid_pose0 humanoid_pose2 sphere torus; do
  for e in off ply; do
    [ -s "$OUT/$s.$e" ] && ok || bad "missing $OUT/$s.$e"
  done
  grep -q "^  $s.off " "$TMP/out" && ok || bad "summary does not list $s.off"
done
# the written humanoids are closed genus-0 manifolds with identical vertex/face counts
for s in humanoid_pose0 humanoid_pose2; do
  "$BIN" info "$OUT/$s.ply" > "$TMP/info" 2>&1 || bad "info $s failed"
  grep -q '^boundary_loops: 0$' "$TMP/info" && grep -q '^manifold: yes$' "$TMP/info" &&
    grep -q '^components: 1$' "$TMP/info" && grep -q '^euler_characteristic: 2$' "$TMP/info" && ok ||
    bad "$s info: $(tr '\n' ' ' < "$TMP/info")"
done
[ "$(sed -n 2p "$OUT/humanoid_pose0.off")" = "$(sed -n 2p "$OUT/humanoid_pose2.off")" ] && ok || bad "pose counts differ"
# pictures: PNG width and height from the IHDR chunk (bytes 16..23, big-endian)
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{ print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4, $5 * 16777216 + $6 * 65536 + $7 * 256 + $8 }'; }
# segment gallery: 2 panels of 480x600 and a 26-pixel title line (text scale 2)
[ "$(png_size "$OUT/humanoid_segments.png")" = "960 626" ] && ok ||
  bad "humanoid_segments.png size $(png_size "$OUT/humanoid_segments.png"), want 960 626"
# the Figure 9 of the humanoid: 5 columns of 480 (Y / STD / ASA / DIFF / segments) + the colour bar's
# column (a quarter panel, 120) by a heading (30) + 2 rows of 600 + a 26-pixel title line
M="$OUT/humanoid_matching.png"
[ -s "$M" ] && head -c 8 "$M" | od -An -c | grep -q "P   N   G" && ok || bad "no PNG $M"
[ "$(png_size "$M")" = "2520 1282" ] && ok || bad "humanoid_matching.png size $(png_size "$M"), want 2520 1282"
grep -q "^  humanoid_matching.png " "$TMP/out" && ok || bad "summary does not list humanoid_matching.png"
"$BIN" info "$OUT/torus.off" | grep -q '^euler_characteristic: 0$' && ok || bad "torus chi"
# eigenvalues are printed, the sphere's are l(l+1): 0, 2, 2, 2 to 3 digits
grep -c '^eigenvalues' "$TMP/out" | grep -q '^4$' && ok || bad "expected 4 eigenvalue lines"
awk '/^== sphere/{s=1} s&&/^eigenvalues/{sub(/^[^:]*: /,""); n=split($0,v," "); exit}
     END{exit !(n>=4 && v[1]<1e-6 && v[1]>-1e-6 && (v[2]-2)^2<1e-4 && (v[4]-2)^2<1e-4)}' "$TMP/out" && ok ||
  bad "sphere eigenvalues: $(awk '/^== sphere/{s=1} s&&/^eigenvalues/{print; exit}' "$TMP/out")"
# running again into the same folder works (overwrites)
"$BIN" demo -o "$OUT" > /dev/null 2>&1 && ok || bad "second run into an existing folder"
# errors: usage (2) and a path that is a file (1)
"$BIN" demo -o > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "-o without value should exit 2"
"$BIN" demo extra > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "stray argument should exit 2"
: > "$TMP/file"
"$BIN" demo -o "$TMP/file" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q '^specseg: error: ' "$TMP/err" && ok || bad "file as output folder: exit $rc"

finish
