#!/usr/bin/env bash
# `specseg refine` on two poses of the built-in humanoid (ground truth = identity): a scrambled
# identity refined comes back closer to it, and polished on the surfaces closer still; the identity of
# a shape onto itself stays; the --fmap output; a prepared shape gives the same map as its mesh; usage
# and input errors.
# Usage: cli_refine.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
demo_outputs "$TMP/d" || { echo "demo failed"; exit 1; }
X="$TMP/d/humanoid_pose0.off"
Y="$TMP/d/humanoid_pose2.off"
nv=$(sed -n 2p "$X" | awk '{print $1}')
num() { sed -n 's/^mean_error: //p' "$1"; }
seq 0 $((nv - 1)) > "$TMP/id.txt"
# every 3rd vertex sent to the next vertex index (a neighbour or close on this mesh), deterministic
awk -v n="$nv" '{ v = $1; if (NR % 3 == 0 && v + 1 < n) v = v + 1; print v }' "$TMP/id.txt" > "$TMP/rough.txt"
opts="--k 20 --zoomout 60"
"$BIN" refine "$X" "$Y" "$TMP/rough.txt" -o "$TMP/ref.txt" $opts > "$TMP/out" 2> "$TMP/err" &&
  grep -q "^$nv -> $nv vertices, refined: k 20, ZoomOut to 60 -> .*ref.txt" "$TMP/out" && ok || bad "refine: $(cat "$TMP/out" "$TMP/err")"
[ "$(wc -l < "$TMP/ref.txt")" -eq "$nv" ] && ok || bad "refined map length"
"$BIN" error "$TMP/rough.txt" "$Y" > "$TMP/e0" 2>&1 && "$BIN" error "$TMP/ref.txt" "$Y" > "$TMP/e1" 2>&1 &&
  awk -v a="$(num "$TMP/e0")" -v b="$(num "$TMP/e1")" 'BEGIN { exit !(b < a) }' && ok ||
  bad "refined error $(num "$TMP/e1") not below the rough map's $(num "$TMP/e0")"
# the identity of a shape onto itself stays the identity
"$BIN" refine "$X" "$X" "$TMP/id.txt" -o "$TMP/same.txt" $opts > /dev/null 2> "$TMP/err" && cmp -s "$TMP/same.txt" "$TMP/id.txt" && ok ||
  bad "identity onto itself: $(cat "$TMP/err")"
# --fmap: KMAX x KMAX; --json names the outputs
"$BIN" refine "$X" "$Y" "$TMP/rough.txt" -o "$TMP/ref2.txt" $opts --fmap "$TMP/C.npy" --json > "$TMP/j" 2> "$TMP/err" &&
  grep -q '"zoomout": 60' "$TMP/j" && grep -q 'C.npy' "$TMP/j" && cmp -s "$TMP/ref.txt" "$TMP/ref2.txt" && ok || bad "--fmap/--json: $(cat "$TMP/j" "$TMP/err")"
[ "$(head -c 128 "$TMP/C.npy" | tr -d '\0' | grep -ao "'shape': ([0-9]*, [0-9]*)")" = "'shape': (60, 60)" ] && ok || bad "C.npy shape"
# --zoomout = --k: no ZoomOut
"$BIN" refine "$X" "$Y" "$TMP/rough.txt" -o "$TMP/proj.txt" --k 20 --zoomout 20 > "$TMP/out" 2>&1 &&
  grep -q "no ZoomOut" "$TMP/out" && ok || bad "no ZoomOut: $(cat "$TMP/out")"
# --polish-only: the map fitted to the surfaces, much nearer the truth than the rough map; --polish:
# after ZoomOut, the same as --polish-only on refine's own output; a prepared shape gives the same
"$BIN" refine "$X" "$Y" "$TMP/rough.txt" -o "$TMP/pol.txt" --polish-only > "$TMP/out" 2> "$TMP/err" &&
  grep -q "^$nv -> $nv vertices, polished on the surfaces -> .*pol.txt" "$TMP/out" && ok || bad "--polish-only: $(cat "$TMP/out" "$TMP/err")"
"$BIN" error "$TMP/pol.txt" "$Y" > "$TMP/e2" 2>&1 &&
  awk -v a="$(num "$TMP/e0")" -v b="$(num "$TMP/e2")" 'BEGIN { exit !(b < 0.5 * a) }' && ok ||
  bad "polished error $(num "$TMP/e2") not below half the rough map's $(num "$TMP/e0")"
"$BIN" refine "$X" "$Y" "$TMP/rough.txt" -o "$TMP/refpol.txt" $opts --polish > "$TMP/out" 2> "$TMP/err" &&
  grep -q "ZoomOut to 60, polished on the surfaces" "$TMP/out" &&
  "$BIN" refine "$X" "$Y" "$TMP/ref.txt" -o "$TMP/refpol2.txt" --polish-only > /dev/null 2>&1 &&
  cmp -s "$TMP/refpol.txt" "$TMP/refpol2.txt" && ok || bad "--polish: $(cat "$TMP/out" "$TMP/err")"
"$BIN" refine "$X" "$Y" "$TMP/rough.txt" -o "$TMP/r.txt" --polish --polish-only > /dev/null 2>&1; [ $? -eq 2 ] && ok ||
  bad "--polish with --polish-only: want exit 2"
"$BIN" refine "$X" "$Y" "$TMP/rough.txt" -o "$TMP/r.txt" --polish-only --fmap "$TMP/c.npy" > /dev/null 2>&1; [ $? -eq 2 ] &&
  ok || bad "--polish-only with --fmap: want exit 2"
# a prepared shape: the same map as from its mesh
"$BIN" prepare "$X" -o "$TMP/x.sss" -k 60 > /dev/null 2>&1 && "$BIN" prepare "$Y" -o "$TMP/y.sss" -k 60 > /dev/null 2>&1 &&
  "$BIN" refine "$TMP/x.sss" "$TMP/y.sss" "$TMP/rough.txt" -o "$TMP/refp.txt" $opts > /dev/null 2> "$TMP/err" &&
  cmp -s "$TMP/refp.txt" "$TMP/ref.txt" && ok || bad "prepared shapes: $(cat "$TMP/err")"
"$BIN" refine "$TMP/x.sss" "$TMP/y.sss" "$TMP/rough.txt" -o "$TMP/polp.txt" --polish-only > /dev/null 2> "$TMP/err" &&
  cmp -s "$TMP/polp.txt" "$TMP/pol.txt" && ok || bad "prepared shapes, --polish-only: $(cat "$TMP/err")"
"$BIN" refine "$TMP/x.sss" "$TMP/y.sss" "$TMP/rough.txt" -o "$TMP/r.txt" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "specseg: error: .*x.sss was prepared with 60 eigenpairs but this refinement needs 110" "$TMP/err" && ok ||
  bad "too few eigenpairs in a .sss: $(cat "$TMP/err")"
# errors: usage (exit 2), then input (exit 1, file and line named)
"$BIN" refine "$X" "$Y" "$TMP/rough.txt" > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "missing -o: want exit 2"
"$BIN" refine "$X" "$Y" -o "$TMP/r.txt" > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "missing map: want exit 2"
"$BIN" refine "$X" "$Y" "$TMP/rough.txt" -o "$TMP/r.txt" --k 30 --zoomout 20 > /dev/null 2> "$TMP/err"; [ $? -eq 2 ] &&
  grep -q "below --k" "$TMP/err" && ok || bad "--zoomout below --k: want exit 2"
head -n 10 "$TMP/id.txt" > "$TMP/short.txt"
"$BIN" refine "$X" "$Y" "$TMP/short.txt" -o "$TMP/r.txt" $opts > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "specseg: error: .*short.txt: 10 lines, but X .* has $nv vertices" "$TMP/err" && ok || bad "short map: $(cat "$TMP/err")"
{ head -n 4 "$TMP/id.txt"; echo "$nv"; tail -n +6 "$TMP/id.txt"; } > "$TMP/off.txt"
"$BIN" refine "$X" "$Y" "$TMP/off.txt" -o "$TMP/r.txt" $opts > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "specseg: error: .*off.txt:5: vertex $nv is not on the target" "$TMP/err" && ok || bad "entry off Y: $(cat "$TMP/err")"
printf 'x\n' > "$TMP/junk.txt"
"$BIN" refine "$X" "$Y" "$TMP/junk.txt" -o "$TMP/r.txt" $opts > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "specseg: error:" "$TMP/err" && ok || bad "junk map: $(cat "$TMP/err")"
# a mesh the pipeline would have to repair (an unreferenced vertex): refused, the file named (the
# map refers to its vertex indices)
awk 'NR == 2 { $1 = $1 + 1 } { print } NR == 2 + '"$nv"' { print "0 0 0" }' "$X" > "$TMP/iso.off"
seq 0 "$nv" > "$TMP/id1.txt"
"$BIN" refine "$TMP/iso.off" "$TMP/iso.off" "$TMP/id1.txt" -o "$TMP/r.txt" $opts > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "specseg: error: .*iso.off: the mesh has 1 unreferenced vertex" "$TMP/err" && ok || bad "unreferenced vertex: $(cat "$TMP/err")"
[ ! -e "$TMP/r.txt" ] && ok || bad "an output written on error"
finish
