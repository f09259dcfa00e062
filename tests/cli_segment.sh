#!/usr/bin/env bash
# `specseg segment` end to end on the demo's synthetic humanoid: labels / centres / coloured PLY /
# timing lines, --no-streamline, and the usage (2) and input (1) errors.
# Usage: cli_segment.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

"$BIN" demo -o "$TMP/demo" > /dev/null 2>&1 || bad "demo failed"
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

finish
