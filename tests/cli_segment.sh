#!/usr/bin/env bash
# `specseg segment` end to end on the demo's synthetic humanoid: labels / centres / coloured PLY /
# timing lines, --no-streamline, the usage (2) and input (1) errors, and the warnings the README
# promises: small holes closed (one component and one of two), no warning for a closed mesh.
# Usage: cli_segment.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

demo_outputs "$TMP/demo" || bad "demo failed"
M="$TMP/demo/humanoid_pose0.off"
if [ ! -s "$M" ]; then
  skip "the demo wrote no humanoid"
  finish
fi
NV=$(sed -n 2p "$M" | awk '{print $1}')

if "$BIN" segment "$M" -o "$TMP/l.txt" --centers "$TMP/c.txt" --ply "$TMP/s.ply" --faces 6000 --timings \
    > "$TMP/out" 2> "$TMP/err"; then ok; else bad "segment exit $? ($(cat "$TMP/err"))"; fi
[ "$(grep -cv '^#' "$TMP/l.txt")" = "$NV" ] && ok || bad "labels: $(wc -l < "$TMP/l.txt") lines, want $NV"
NS=$(grep -cv '^#' "$TMP/c.txt")
[ "$NS" -ge 2 ] && ok || bad "centres: $NS"
# labels cover 0..NS-1 exactly
[ "$(grep -v '^#' "$TMP/l.txt" | sort -n | uniq | wc -l)" = "$NS" ] && ok || bad "labels do not use every segment"
grep -v '^#' "$TMP/l.txt" | awk -v n="$NS" '$1<0||$1>=n{bad=1} END{exit bad}' && ok || bad "label out of range"
# each centre is an input vertex whose label is its own segment
awk 'NR==FNR{if($0!~/^#/)lab[k++]=$1; next} !/^#/{if(lab[$1]!=s++) bad=1} END{exit bad}' "$TMP/l.txt" "$TMP/c.txt" &&
  ok || bad "a centre lies outside its segment"
for st in smooth remesh spectrum critical ivd total; do
  grep -Eq "^timing: $st [0-9.]+$" "$TMP/err" && ok || bad "no timing line for $st"
done
head -c 3 "$TMP/s.ply" | grep -q ply && ok || bad "PLY header"
grep -aq "property uchar red" "$TMP/s.ply" && ok || bad "PLY without colours"
grep -aq "element vertex $NV" "$TMP/s.ply" && ok || bad "PLY vertex count"

"$BIN" segment "$M" -o "$TMP/l2.txt" --no-streamline > /dev/null 2>&1 && ok || bad "--no-streamline failed"
[ "$(grep -cv '^#' "$TMP/l2.txt")" = "$NV" ] && ok || bad "--no-streamline labels"
# deterministic
"$BIN" segment "$M" -o "$TMP/l3.txt" --faces 6000 > /dev/null 2>&1 && cmp -s "$TMP/l.txt" "$TMP/l3.txt" && ok ||
  bad "two runs differ"

# errors
"$BIN" segment > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "no arguments should exit 2"
"$BIN" segment "$M" > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "missing -o should exit 2"
"$BIN" segment "$M" -o "$TMP/x.txt" --faces 0 > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "--faces 0 should exit 2"
"$BIN" segment "$M" -o "$TMP/x.txt" --bogus > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "unknown option should exit 2"
"$BIN" segment "$TMP/none.off" -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; [ $? -eq 1 ] && ok || bad "missing mesh should exit 1"
grep -q '^specseg: error: ' "$TMP/err" && ok || bad "error message format"
"$BIN" segment "$M" -o "$TMP/nodir/x.txt" > /dev/null 2>&1; [ $? -eq 1 ] && ok || bad "unwritable output should exit 1"

# holes: the sphere without one triangle, and the same beside a shifted closed copy (two components)
S="$TMP/demo/sphere.off"
"$BIN" segment "$S" -o "$TMP/x.txt" --faces 3000 > /dev/null 2> "$TMP/err" && [ ! -s "$TMP/err" ] && ok ||
  bad "a closed mesh gets a warning: $(cat "$TMP/err")"
awk 'NR == 2 { print $1, $2 - 1, $3; next } NR == 3 + n { next } { print }' n="$(sed -n 2p "$S" | awk '{print $1}')" "$S" > "$TMP/hole.off"
"$BIN" segment "$TMP/hole.off" -o "$TMP/x.txt" --faces 3000 > /dev/null 2> "$TMP/err" && ok || bad "segment a holed sphere"
grep -q "^specseg: warning: .*hole.off: 1 hole (boundary loop) closed internally" "$TMP/err" && ok || bad "no hole warning: $(cat "$TMP/err")"
awk 'NR == 2 { nv = $1; nf = $2; print 2 * nv, 2 * nf - 1, 0; next }
     NR > 2 && NR <= 2 + nv { v[NR] = $0; print; next }
     NR == 3 + nv { for (i = 3; i <= 2 + nv; i++) { split(v[i], c, " "); print c[1] + 5, c[2], c[3] } }
     NR > 2 + nv { f[++k] = $0; print }
     END { for (i = 2; i <= k; i++) { split(f[i], c, " "); print 3, c[2] + nv, c[3] + nv, c[4] + nv } }' "$S" > "$TMP/two.off"
"$BIN" info "$TMP/two.off" | grep -q "^components: 2$" || bad "the two-component test mesh is not what it should be"
"$BIN" segment "$TMP/two.off" -o "$TMP/x.txt" --faces 3000 > /dev/null 2> "$TMP/err" && ok || bad "segment two components"
grep -q "component 2 (input vertex [0-9]* onwards): 1 hole (boundary loop) closed internally" "$TMP/err" && ok ||
  bad "no hole warning for the second component: $(cat "$TMP/err")"
printf '0\n500\n1000\n' > "$TMP/lm3.txt"
"$BIN" match "$TMP/hole.off" "$S" --landmarks "$TMP/lm3.txt" --k 10 -o "$TMP/m.txt" > /dev/null 2> "$TMP/err" && ok ||
  bad "match a holed sphere: $(cat "$TMP/err")"
grep -q "^specseg: warning: .*hole.off: 1 hole (boundary loop) closed internally for the segmentation" "$TMP/err" &&
  ! grep -q "sphere.off: .*hole" "$TMP/err" && ok || bad "match: no hole warning: $(cat "$TMP/err")"

finish
