#!/usr/bin/env bash
# `specseg smooth` and `specseg remesh` end to end: outputs written and readable, the remesh
# quality line on stderr, connectivity kept by smooth, usage errors exit 2, input errors exit 1.
# Usage: cli_streamline.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

# a closed input: an octahedron
IN="$TMP/octa.off"
printf 'OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n' > "$IN"
printf '3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n' >> "$IN"

if "$BIN" smooth "$IN" -o "$TMP/s.off" --steps 3 --dt 1e-4 2> "$TMP/err"; then ok; else bad "smooth exit $? ($(cat "$TMP/err"))"; fi
[ "$(sed -n 2p "$IN")" = "$(sed -n 2p "$TMP/s.off")" ] && ok || bad "smooth changed the counts"
"$BIN" smooth "$IN" -o "$TMP/s2.ply" --bbox 2> "$TMP/err" && ok || bad "smooth --bbox failed ($(cat "$TMP/err"))"

if "$BIN" remesh "$TMP/s.off" -o "$TMP/r.ply" --faces 1000 2> "$TMP/err"; then ok; else bad "remesh exit $? ($(cat "$TMP/err"))"; fi
grep -Eq '^remesh: faces [0-9]+, min angle >= 30: [0-9.]+%, valence 6: [0-9.]+%, max deviation / bbox diag: ' "$TMP/err" && ok ||
  bad "quality line: $(cat "$TMP/err")"
"$BIN" info "$TMP/r.ply" > "$TMP/info" 2>&1 || bad "info on the remesh failed"
grep -q '^manifold: yes$' "$TMP/info" && grep -q '^boundary_loops: 0$' "$TMP/info" &&
  grep -q '^euler_characteristic: 2$' "$TMP/info" && ok || bad "remesh not a closed sphere: $(tr '\n' ' ' < "$TMP/info")"
faces=$(sed -n 's/^faces: //p' "$TMP/info")
[ "${faces:-0}" -ge 950 ] && [ "${faces:-0}" -le 1050 ] && ok || bad "remesh faces $faces"

# usage errors: exit 2
for args in "" "$IN" "$IN -o" "$IN -o x.off --steps -1" "$IN -o x.off --dt 0" "$IN -o x.off --bogus"; do
  "$BIN" smooth $args > /dev/null 2>&1; rc=$?
  [ $rc -eq 2 ] && ok || bad "smooth '$args' exit $rc, want 2"
done
# an out-of-range value says the range (was "--dt wants a positive number" for 1e300)
"$BIN" smooth "$IN" -o x.off --dt 1e300 > /dev/null 2> "$TMP/err"; [ $? -eq 2 ] &&
  grep -q "^specseg: usage: smooth: --dt wants a time step in (0, 1e6\], got '1e300'" "$TMP/err" && ok || bad "--dt 1e300: $(cat "$TMP/err")"
# targets beyond the documented bound are refused at once, with the range (5e6 took > 400 s)
for cmd in remesh segment; do
  timeout 10 "$BIN" $cmd "$IN" -o "$TMP/x.out" --faces 5000000 > /dev/null 2> "$TMP/err"; [ $? -eq 2 ] &&
    grep -q "^specseg: usage: $cmd: --faces .*4.* 2000000" "$TMP/err" && ok || bad "$cmd --faces 5000000: $(cat "$TMP/err")"
done
for args in "" "$IN" "$IN -o x.off --faces 2" "$IN -o x.off --faces abc"; do
  "$BIN" remesh $args > /dev/null 2>&1; rc=$?
  [ $rc -eq 2 ] && ok || bad "remesh '$args' exit $rc, want 2"
done
# input errors: exit 1 with a message
"$BIN" smooth "$TMP/missing.off" -o "$TMP/x.off" 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q '^specseg: error: ' "$TMP/err" && ok || bad "missing file exit $rc"
# an open mesh (one triangle) is refused by remesh
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$TMP/tri.off"
"$BIN" remesh "$TMP/tri.off" -o "$TMP/x.off" 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q 'closed' "$TMP/err" && ok || bad "open mesh exit $rc ($(cat "$TMP/err"))"

finish
