#!/usr/bin/env bash
# `specseg eigs` end to end: eigenvalues on stdout (k lines, ascending, first ~0), the .npy written
# with the right size, usage errors exit 2, input errors (missing file, malformed corpus) exit 1,
# zero-area vertices tolerated with a warning, FAUST k=100 when the shared data is there.
# Usage: cli_eigs.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
HERE=$(cd "$(dirname "$0")" && pwd)
TESTS=${SS_TEST_DIR:-$HERE}
. "$(dirname "$0")/lib_cli.sh"

# regular icosahedron (12 vertices, 20 faces) and the same with an unreferenced 13th vertex
ico() {
  local extra=$1
  local t=1.618033988749895
  echo OFF
  echo "$((12 + extra)) 20 0"
  for v in "-1 $t 0" "1 $t 0" "-1 -$t 0" "1 -$t 0" "0 -1 $t" "0 1 $t" "0 -1 -$t" "0 1 -$t" \
           "$t 0 -1" "$t 0 1" "-$t 0 -1" "-$t 0 1"; do echo "$v"; done
  [ "$extra" = 1 ] && echo "5 5 5"
  for f in "0 11 5" "0 5 1" "0 1 7" "0 7 10" "0 10 11" "1 5 9" "5 11 4" "11 10 2" "10 7 6" "7 1 8" \
           "3 9 4" "3 4 2" "3 2 6" "3 6 8" "3 8 9" "4 9 5" "2 4 11" "6 2 10" "8 6 7" "9 8 1"; do echo "3 $f"; done
}
ico 0 > "$TMP/ico.off"
ico 1 > "$TMP/ico13.off"

# valid run: 4 eigenvalues, first ~0, next three equal (l = 1 of an icosahedral shape), ascending
if "$BIN" eigs "$TMP/ico.off" -k 4 --evecs "$TMP/ev.npy" > "$TMP/out" 2> "$TMP/err"; then ok; else bad "eigs exit $? ($(cat "$TMP/err"))"; fi
[ "$(wc -l < "$TMP/out")" -eq 4 ] && ok || bad "expected 4 lines, got $(wc -l < "$TMP/out")"
awk 'NR==1{if ($1 > 1e-8 || $1 < -1e-8) exit 1} NR>1{if ($1 < prev) exit 1} {prev=$1} NR>=2{v[NR]=$1}
     END{if ((v[2]-v[4])^2 > 1e-16*v[2]^2) exit 1}' "$TMP/out" && ok || bad "eigenvalues: $(tr '\n' ' ' < "$TMP/out")"
# .npy: 128-byte header for shape (12, 4) plus 48 doubles
[ "$(head -c 6 "$TMP/ev.npy" | tail -c 5)" = "NUMPY" ] && ok || bad "npy magic"
[ "$(wc -c < "$TMP/ev.npy")" -eq $((128 + 12 * 4 * 8)) ] && ok || bad "npy size $(wc -c < "$TMP/ev.npy")"
grep -qa "'shape': (12, 4)" "$TMP/ev.npy" && ok || bad "npy shape"
# options
"$BIN" eigs "$TMP/ico.off" -k 3 --mass voronoi --sigma -0.5 > "$TMP/out" 2> "$TMP/err" && [ "$(wc -l < "$TMP/out")" -eq 3 ] && ok ||
  bad "voronoi/sigma run: $(cat "$TMP/err")"
# unreferenced vertex: warning, still 13 rows in the eigenvectors
if "$BIN" eigs "$TMP/ico13.off" -k 2 --evecs "$TMP/ev13.npy" > "$TMP/out" 2> "$TMP/err"; then ok; else bad "ico13 exit $?"; fi
grep -q "specseg: warning:" "$TMP/err" && ok || bad "ico13: no warning"
[ "$(wc -c < "$TMP/ev13.npy")" -eq $((128 + 13 * 2 * 8)) ] && ok || bad "ico13 npy size $(wc -c < "$TMP/ev13.npy")"

# expect CODE ARGS...: exit code and the matching stderr prefix
expect() {
  local want=$1
  shift
  timeout 20 "$BIN" eigs "$@" > "$TMP/out" 2> "$TMP/err"
  local rc=$?
  local prefix='specseg: error:'
  [ "$want" = 2 ] && prefix='specseg: usage:'
  if [ $rc -ne "$want" ]; then bad "exit $rc (want $want): eigs $* -- $(head -c 300 "$TMP/err")"; return; fi
  grep -q "^$prefix" "$TMP/err" && ok || bad "no '$prefix' line: eigs $*"
  grep -qE 'AddressSanitizer|runtime error:' "$TMP/err" && bad "sanitizer report: eigs $*"
}
expect 2 "$TMP/ico.off"
expect 2 "$TMP/ico.off" -k 12
expect 2 "$TMP/ico.off" -k 0
expect 2 "$TMP/ico.off" -k -3
expect 2 "$TMP/ico.off" -k abc
expect 2 "$TMP/ico.off" -k
expect 2 "$TMP/ico.off" -k 3 --mass cotan
expect 2 "$TMP/ico.off" -k 3 --sigma nan
expect 2 "$TMP/ico.off" -k 3 --bogus
expect 2 -k 3
expect 2 "$TMP/ico.off" "$TMP/ico.off" -k 3
expect 1 "$TMP/missing.off" -k 3
expect 2 "$TMP" -k 3   # a folder is a batch, which needs -o OUTDIR
expect 1 "$TMP/ico.off" -k 3 --evecs "$TMP/no/such/dir/ev.npy"
expect 1 "$TMP/ico.off" -k 1 --sigma 0.0 --mass barycentric --evecs "$TMP/no/x.npy"
if [ -d "$TESTS/data/malformed" ]; then
  for f in "$TESTS"/data/malformed/*; do
    [ -f "$f" ] && expect 1 "$f" -k 1
  done
fi

# k too close to n: the message says so and gives a k that works (was "ARPACK converged 638 of 640 ...
# (increase ncv)" / "cannot compute 1 more eigenpairs in a space of dimension 1")
expect 1 "$TMP/ico.off" -k 11
grep -q "ico.off: eigs: k = 11 is too close to the number of vertices (12).*use k <= 6" "$TMP/err" && ok ||
  bad "k = n - 1: $(cat "$TMP/err")"
"$BIN" eigs "$TMP/ico.off" -k 6 > /dev/null 2>&1 && ok || bad "the advised k = 6 fails"

# a NaN vertex is an error naming it (was: a zero-area warning, then success); coordinates beyond
# 1e70 (x1e300) or a mesh spanning less than 1e-70 are refused with what to do
expect 1 "$TESTS/data/info/nan_vertex.off" -k 2
grep -q "nan_vertex.off: .*vertex 2 has a non-finite coordinate" "$TMP/err" && ! grep -q warning "$TMP/err" && ok ||
  bad "NaN vertex: $(cat "$TMP/err")"
awk 'NR <= 2 || NF != 3 { print; next } { print $1 * 1e300, $2 * 1e300, $3 * 1e300 }' "$TMP/ico.off" > "$TMP/ico_big.off"
expect 1 "$TMP/ico_big.off" -k 3
grep -q "ico_big.off: .*magnitude 1.62e+300, beyond the supported 1e+70.*scale the mesh down" "$TMP/err" && ok ||
  bad "x1e300: $(cat "$TMP/err")"
awk 'NR <= 2 || NF != 3 { print; next } { print $1 * 1e-100, $2 * 1e-100, $3 * 1e-100 }' "$TMP/ico.off" > "$TMP/ico_tiny.off"
expect 1 "$TMP/ico_tiny.off" -k 3
grep -q "ico_tiny.off: .*spans only .*scale the mesh up" "$TMP/err" && ok || bad "x1e-100: $(cat "$TMP/err")"

# FAUST: 100 ascending eigenvalues, the first ~0
if [ -n "${SS_DATA_DIR:-}" ] && [ -f "$SS_DATA_DIR/faust/tr_reg_000.off" ]; then
  if "$BIN" eigs "$SS_DATA_DIR/faust/tr_reg_000.off" -k 100 > "$TMP/out" 2> "$TMP/err"; then ok; else bad "FAUST exit $?"; fi
  [ "$(wc -l < "$TMP/out")" -eq 100 ] && ok || bad "FAUST: $(wc -l < "$TMP/out") lines"
  awk 'NR==1{if ($1 > 1e-8 || $1 < -1e-8) exit 1} NR>1{if ($1 < prev) exit 1} {prev=$1} NR==2{if ($1 < 1) exit 1}' "$TMP/out" &&
    ok || bad "FAUST eigenvalues not ascending from 0"
else
  skip "no data folder: FAUST eigs"
fi

finish
