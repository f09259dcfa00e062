#!/usr/bin/env bash
# Scale invariance end to end (issue 13, item 4): `specseg segment` and `specseg geodesic` on a mesh
# scaled by 2^-20 / 2^20 (exact: the same labels and centres, distances exactly x s), by 1e-6 / 1e6
# (rounded coordinates, a 1-ulp perturbation: the same segment count, labels within 1%, distances x s
# to round-off), and by 1e80 / 1e-80 (outside the double range of squared lengths: a clear error).
# The mesh: the demo's synthetic humanoid (written with %.17g, so read back exactly).
# Usage: cli_scale.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

demo_outputs "$TMP/demo" || bad "demo failed"
if [ ! -s "$TMP/demo/humanoid_pose0.off" ]; then
  skip "the demo wrote no humanoid"
  finish
fi
cp "$TMP/demo/humanoid_pose0.off" "$TMP/m.off"
NV=$(sed -n 2p "$TMP/m.off" | awk '{print $1}')
# the mesh times S (an awk expression: 2^-20, 1e6, ...), coordinates written losslessly
scale() { awk -v e="$1" 'BEGIN { s = e + 0; if (e ~ /\^/) { split(e, p, "\\^"); s = p[1] ^ p[2] } }
  NR <= 2 || NF != 3 { print; next } { printf "%.17g %.17g %.17g\n", $1 * s, $2 * s, $3 * s }' "$TMP/m.off"; }
# S as a number for awk comparisons
num() { awk -v e="$1" 'BEGIN { if (e ~ /\^/) { split(e, p, "\\^"); printf "%.17g", p[1] ^ p[2] } else printf "%.17g", e + 0 }'; }

SEG=(--faces 6000)
if ! "$BIN" segment "$TMP/m.off" "${SEG[@]}" -o "$TMP/l1.txt" --centers "$TMP/c1.txt" > /dev/null 2> "$TMP/err"; then
  bad "segment x1: $(cat "$TMP/err")"
  finish
fi
NC=$(grep -cv '^#' "$TMP/c1.txt")
[ "$NC" -ge 6 ] && ok || bad "the humanoid has $NC segments"
SRC=(--source 0 --source $((NV / 2)))
for meth in exact graph; do
  "$BIN" geodesic "$TMP/m.off" "${SRC[@]}" --method $meth -o "$TMP/d1_$meth.txt" 2> "$TMP/err" || bad "geodesic $meth x1: $(cat "$TMP/err")"
done

for S in '2^-20' '2^20' 1e-6 1e6; do
  scale "$S" > "$TMP/s.off"
  s=$(num "$S")
  exact=0; case $S in *^*) exact=1 ;; esac
  if "$BIN" segment "$TMP/s.off" "${SEG[@]}" -o "$TMP/l.txt" --centers "$TMP/c.txt" > /dev/null 2> "$TMP/err"; then
    if [ $exact = 1 ]; then
      cmp -s "$TMP/l.txt" "$TMP/l1.txt" && cmp -s "$TMP/c.txt" "$TMP/c1.txt" && ok ||
        bad "segment x$S: labels or centres differ from x1 ($(paste "$TMP/l.txt" "$TMP/l1.txt" | awk '$1 != $2' | wc -l) labels)"
    else
      [ "$(grep -cv '^#' "$TMP/c.txt")" = "$NC" ] && ok || bad "segment x$S: $(grep -cv '^#' "$TMP/c.txt") segments, x1 has $NC"
      nd=$(paste "$TMP/l.txt" "$TMP/l1.txt" | awk '$1 != $2' | wc -l)
      [ "$nd" -le $((NV / 100)) ] && ok || bad "segment x$S: $nd of $NV labels differ from x1"
    fi
  else bad "segment x$S: $(cat "$TMP/err")"; fi
  for meth in exact graph; do
    if "$BIN" geodesic "$TMP/s.off" "${SRC[@]}" --method $meth -o "$TMP/d.txt" 2> "$TMP/err"; then
      # exact factors: d == s * d1 to the bit; others: |d / s / d1 - 1| <= 1e-12
      paste "$TMP/d.txt" "$TMP/d1_$meth.txt" | awk -v s="$s" -v exact=$exact '
        { if (exact) { if ($1 != $2 * s) bad++ } else if ($2 > 0) { r = $1 / s / $2 - 1; if (r < 0) r = -r; if (r > 1e-12) bad++ }
          else if ($1 != 0) bad++ }
        END { exit bad > 0 || NR == 0 }' && ok || bad "geodesic $meth x$S: distances are not x$S those of x1"
    else bad "geodesic $meth x$S: $(cat "$TMP/err")"; fi
  done
done

# beyond the double range of squared lengths: refused with what to do
for S in 1e80 1e-80; do
  scale "$S" > "$TMP/x.off"
  want="scale the mesh down"; [ "$S" = 1e-80 ] && want="scale the mesh up"
  for cmd in segment geodesic; do
    if [ $cmd = segment ]; then "$BIN" segment "$TMP/x.off" -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"
    else "$BIN" geodesic "$TMP/x.off" --source 0 -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; fi
    rc=$?
    [ $rc -eq 1 ] && grep -q "^specseg: error: .*x.off: .*$want" "$TMP/err" && ok || bad "$cmd x$S: exit $rc, $(cat "$TMP/err")"
  done
done
finish
