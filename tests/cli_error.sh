#!/usr/bin/env bash
# `specseg error`: geodesic error of a map on a unit-edge octahedron (exact values), the symmetric
# variant, the per-vertex output, usage and input errors.
# Usage: cli_error.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
s=0.70710678118654752 # edge 1: vertices (±s,0,0), (0,±s,0), (0,0,±s); area 8·√3/4 = 2√3
cat > "$TMP/oct.off" <<MESH
OFF
6 8 0
$s 0 0
-$s 0 0
0 $s 0
0 -$s 0
0 0 $s
0 0 -$s
3 0 2 4
3 2 1 4
3 1 3 4
3 3 0 4
3 2 0 5
3 1 2 5
3 3 1 5
3 0 3 5
MESH
printf '0\n1\n2\n3\n4\n5\n' > "$TMP/id.txt"
printf '2\n1\n2\n3\n4\n5\n' > "$TMP/one.txt"   # vertex 0 sent to a neighbour: error 1 on one vertex of 6
printf '1\n0\n2\n3\n4\n5\n' > "$TMP/sym.txt"   # 0 <-> 1 mirror
printf '1\n0\n2\n3\n4\n5\n' > "$TMP/flip.txt"  # the map is the mirror itself
num() { sed -n 's/^mean_error: //p' "$1"; }
close() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d < 1e-6) }'; }
"$BIN" error "$TMP/id.txt" "$TMP/oct.off" > "$TMP/out" 2>&1 && close "$(num "$TMP/out")" 0 && ok || bad "identity: $(cat "$TMP/out")"
# 1/6 · 1/√(2√3)
want=$(awk 'BEGIN { printf "%.9f", 1 / 6 / sqrt(2 * sqrt(3)) }')
"$BIN" error "$TMP/one.txt" "$TMP/oct.off" -o "$TMP/e.txt" > "$TMP/out" 2>&1 && close "$(num "$TMP/out")" "$want" && ok ||
  bad "one vertex off: $(cat "$TMP/out") want $want"
[ "$(wc -l < "$TMP/e.txt")" -eq 6 ] && ok || bad "per-vertex file"
# the mirror map itself has a positive error, and zero once the mirror is allowed
"$BIN" error "$TMP/flip.txt" "$TMP/oct.off" --gt "$TMP/id.txt" > "$TMP/out" 2>&1 && awk -v v="$(num "$TMP/out")" 'BEGIN { exit !(v > 0) }' && ok ||
  bad "flip: $(cat "$TMP/out")"
"$BIN" error "$TMP/flip.txt" "$TMP/oct.off" --sym "$TMP/sym.txt" > "$TMP/out" 2>&1 && close "$(num "$TMP/out")" 0 && ok ||
  bad "flip with symmetry: $(cat "$TMP/out")"
# errors
"$BIN" error "$TMP/id.txt" > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "missing mesh: want exit 2"
"$BIN" error "$TMP/id.txt" "$TMP/oct.off" --bogus > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "bad option: want exit 2"
printf '0\n9\n' > "$TMP/bad.txt"
"$BIN" error "$TMP/bad.txt" "$TMP/oct.off" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] && grep -q "specseg: error:" "$TMP/err" && ok || bad "out-of-range map: want exit 1"
# out-of-range entries name the file and its line (comments and blank lines counted), from a file
# or standard input, for the map, the ground truth and the symmetry map (was "map line 2: ...")
printf '# a map\n0\n\n1\n2\n3\n4\n-1\n' > "$TMP/bad6.txt"
"$BIN" error "$TMP/bad6.txt" "$TMP/oct.off" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "error: .*bad6.txt:8: vertex -1 is not on the target (.*oct.off has vertices 0..5)" "$TMP/err" && ok ||
  bad "out-of-range map entry: $(cat "$TMP/err")"
"$BIN" error - "$TMP/oct.off" < "$TMP/bad.txt" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "error: <stdin>:2: vertex 9 is not on the target" "$TMP/err" && ok || bad "out-of-range map on stdin: $(cat "$TMP/err")"
"$BIN" error "$TMP/id.txt" "$TMP/oct.off" --gt "$TMP/bad6.txt" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "error: .*bad6.txt:8: vertex -1 is not on the target" "$TMP/err" && ok || bad "out-of-range GT entry: $(cat "$TMP/err")"
printf '1\n0\n2\n3\n6\n5\n' > "$TMP/badsym.txt"
"$BIN" error "$TMP/id.txt" "$TMP/oct.off" --sym "$TMP/badsym.txt" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "error: .*badsym.txt:5: vertex 6 is not a vertex of X" "$TMP/err" && ok || bad "out-of-range symmetry entry: $(cat "$TMP/err")"
"$BIN" error "$TMP/nope.txt" "$TMP/oct.off" > /dev/null 2>&1; [ $? -eq 1 ] && ok || bad "missing map: want exit 1"
"$BIN" error "$TMP/id.txt" "$TMP/oct.off" --gt "$TMP/bad.txt" > /dev/null 2>&1; [ $? -eq 1 ] && ok || bad "short gt: want exit 1"
# the map's length (issue 32, item 3): the identity needs one line per vertex of Y; with --gt the
# ground truth's length, and X (--x) its vertex count; a map one line short or long is refused
head -5 "$TMP/id.txt" > "$TMP/short.txt"
"$BIN" error "$TMP/short.txt" "$TMP/oct.off" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "error: .*short.txt: 5 lines, but .*oct.off has 6 vertices" "$TMP/err" && ok || bad "short map, identity: $(cat "$TMP/err")"
{ cat "$TMP/id.txt"; echo 0; } > "$TMP/long.txt"
"$BIN" error "$TMP/long.txt" "$TMP/oct.off" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] && grep -q "7 lines" "$TMP/err" && ok ||
  bad "long map, identity: $(cat "$TMP/err")"
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$TMP/tet.off"
"$BIN" error "$TMP/one.txt" "$TMP/oct.off" --gt "$TMP/id.txt" --x "$TMP/oct.off" > "$TMP/out" 2>&1 && ok || bad "--x: $(cat "$TMP/out")"
"$BIN" error "$TMP/one.txt" "$TMP/oct.off" --gt "$TMP/id.txt" --x "$TMP/tet.off" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "error: .*one.txt: 6 lines, but X (.*tet.off) has 4 vertices" "$TMP/err" && ok || bad "--x mismatch: $(cat "$TMP/err")"
"$BIN" error "$TMP/one.txt" "$TMP/tet.off" --x "$TMP/oct.off" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] && ok ||
  bad "identity onto a smaller Y: $(cat "$TMP/err")"
# the synopsis names every option (--json was missing)
"$BIN" error --help | head -1 | grep -q -- '--json' && "$BIN" error --help | head -1 | grep -q -- '--x MESH' && ok ||
  bad "error --help synopsis: $("$BIN" error --help | head -1)"
finish
