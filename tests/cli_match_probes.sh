#!/usr/bin/env bash
# `specseg match` with segments as probes (paper §6) on two poses of the built-in humanoid (ground
# truth = identity): --probes std|asa|diff, --pairs file format, landmark files, errors.
# Usage: cli_match_probes.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
demo_outputs "$TMP/d" "$TMP/demo.out" || { echo "demo failed"; exit 1; }
grep -q '^DIFF mean geodesic error' "$TMP/demo.out" && grep -q '^STD  mean geodesic error' "$TMP/demo.out" && ok ||
  bad "demo has no matching stage"
X="$TMP/d/humanoid_pose0.off"
Y="$TMP/d/humanoid_pose2.off"
nv=$(sed -n 2p "$X" | awk '{print $1}')
# head, hands, feet as the demo found them; written as 'i' and 'i j' lines
sed -n 's/^landmarks (head, left hand, right hand, left foot, right foot): //p' "$TMP/demo.out" | tr ' ' '\n' > "$TMP/l"
[ "$(grep -c . "$TMP/l")" -eq 5 ] && ok || bad "landmarks from the demo"
{ echo "# head"; sed -n 1p "$TMP/l"; sed -n '2,5p' "$TMP/l" | awk '{print $1, $1}'; } > "$TMP/lm.txt"
for p in std asa diff; do
  "$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --probes $p --k 30 --no-refine -o "$TMP/map_$p.txt" --pairs "$TMP/pairs_$p.txt" \
    --timings > "$TMP/out_$p" 2> "$TMP/err_$p" && ok || bad "match --probes $p: $(cat "$TMP/err_$p")"
  [ "$(grep -c . "$TMP/map_$p.txt")" -eq "$nv" ] && ok || bad "$p: map line count"
  awk -v n="$nv" '!($1 ~ /^[0-9]+$/ && $1 < n && NF == 1) { exit 1 }' "$TMP/map_$p.txt" && ok || bad "$p: map entries"
  grep -q '^timing: pair ' "$TMP/err_$p" && grep -q '^timing: segment ' "$TMP/err_$p" && grep -q '^timing: total ' "$TMP/err_$p" &&
    ok || bad "$p: timings on stderr"
  "$BIN" error "$TMP/map_$p.txt" "$Y" > "$TMP/e_$p" 2>&1 && ok || bad "$p: specseg error"
done
# pairs: 'x y' input vertices, at least two pairs, same file for every probe set
np=$(grep -c . "$TMP/pairs_diff.txt")
[ "$np" -ge 2 ] && ok || bad "only $np pairs"
awk -v n="$nv" '!(NF == 2 && $1 ~ /^[0-9]+$/ && $2 ~ /^[0-9]+$/ && $1 < n && $2 < n) { exit 1 }' "$TMP/pairs_diff.txt" && ok ||
  bad "pairs format: $(head -3 "$TMP/pairs_diff.txt")"
cmp -s "$TMP/pairs_std.txt" "$TMP/pairs_diff.txt" && ok || bad "pairs differ between probe sets"
# STD without --pairs: nothing segmented or paired, the same map
"$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --probes std --k 30 --no-refine -o "$TMP/map_std0.txt" --timings \
  > "$TMP/out_std0" 2> "$TMP/err_std0" && cmp -s "$TMP/map_std0.txt" "$TMP/map_std.txt" && ok || bad "std without --pairs: map differs"
grep -q 'no segments (std)' "$TMP/out_std0" && grep -q '^timing: segment 0.000000' "$TMP/err_std0" && ok ||
  bad "std without --pairs segmented: $(cat "$TMP/out_std0" "$TMP/err_std0")"
for p in std diff; do eval "e_$p=\$(sed -n 's/^mean_error: //p' \"\$TMP/e_$p\")"; done
awk -v s="${e_std:-1}" -v d="${e_diff:-1}" 'BEGIN { exit !(d < 0.1 && s < 0.1) }' && ok || bad "errors std ${e_std:-?} diff ${e_diff:-?}"
# segment profiles: each runs and gives a valid map; the soft one differs from the default tent
for sp in indicator soft; do
  "$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --k 30 --no-refine --segment-profile $sp -o "$TMP/map_sp_$sp.txt" > /dev/null \
    2> "$TMP/err" && ok || bad "--segment-profile $sp: $(cat "$TMP/err")"
  [ "$(grep -c . "$TMP/map_sp_$sp.txt")" -eq "$nv" ] && ok || bad "--segment-profile $sp: map line count"
done
cmp -s "$TMP/map_sp_soft.txt" "$TMP/map_diff.txt" && bad "soft profile gave the tent's map" || ok
# the default output: refined (a valid map, reported as such), no worse than 0.1
"$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --k 30 --zoomout 60 --descr-k 60 -o "$TMP/map_ref.txt" > "$TMP/out_ref" 2> "$TMP/err" &&
  ok || bad "default (refined) match: $(cat "$TMP/err")"
grep -q 'refined: ' "$TMP/out_ref" && ok || bad "refined run does not say what it returned: $(cat "$TMP/out_ref")"
"$BIN" error "$TMP/map_ref.txt" "$Y" > "$TMP/e_ref" 2>&1 && ok || bad "refined: specseg error"
e_ref=$(sed -n 's/^mean_error: //p' "$TMP/e_ref")
awk -v r="${e_ref:-1}" 'BEGIN { exit !(r < 0.1) }' && ok || bad "refined error ${e_ref:-?}"
# 3 landmarks: no segment probes, and a note says so
sed -n 1,3p "$TMP/l" > "$TMP/lm3.txt"
"$BIN" match "$X" "$Y" --landmarks "$TMP/lm3.txt" --k 30 --no-refine -o "$TMP/m3.txt" > "$TMP/out3" 2> "$TMP/err" && ok ||
  bad "3 landmarks: $(cat "$TMP/err")"
grep -q '^note: .*no segment probes' "$TMP/out3" && ok || bad "3 landmarks: no note: $(cat "$TMP/out3")"
"$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --segment-profile round -o "$TMP/m.txt" > /dev/null 2>&1
[ $? -eq 2 ] && ok || bad "--segment-profile round: want exit 2"
# errors: bad landmark index -> 1, bad option values -> 2
printf '0\n%d 3\n' "$nv" > "$TMP/badlm.txt"
"$BIN" match "$X" "$Y" --landmarks "$TMP/badlm.txt" -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"
[ $? -eq 1 ] && grep -q '^specseg: error: .*badlm.txt:2' "$TMP/err" && ok || bad "landmark out of range on X: $(cat "$TMP/err")"
printf '0 %d\n' "$nv" > "$TMP/badlm.txt"
"$BIN" match "$X" "$Y" --landmarks "$TMP/badlm.txt" -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"
[ $? -eq 1 ] && grep -q '^specseg: error: .*not on Y' "$TMP/err" && ok || bad "landmark out of range on Y: $(cat "$TMP/err")"
printf -- '-3\n' > "$TMP/badlm.txt"
"$BIN" match "$X" "$Y" --landmarks "$TMP/badlm.txt" -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"
[ $? -eq 1 ] && grep -q '^specseg: error:' "$TMP/err" && ok || bad "negative landmark: $(cat "$TMP/err")"
printf '# nothing\n\n' > "$TMP/badlm.txt"
"$BIN" match "$X" "$Y" --landmarks "$TMP/badlm.txt" -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"
[ $? -eq 1 ] && grep -q '^specseg: error:' "$TMP/err" && ok || bad "empty landmarks: $(cat "$TMP/err")"
"$BIN" match "$X" "$Y" --landmarks "$TMP/none.txt" -o "$TMP/m.txt" > /dev/null 2>&1; [ $? -eq 1 ] && ok || bad "missing landmark file"
"$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" -o "$TMP/m.txt" --k 40 --zoomout 30 > /dev/null 2>&1; [ $? -eq 2 ] && ok ||
  bad "--zoomout below --k: want exit 2"
"$BIN" match "$X" --landmarks "$TMP/lm.txt" -o "$TMP/m.txt" > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "one mesh: want exit 2"
[ ! -e "$TMP/m.txt" ] && ok || bad "a failed run wrote the map"
finish
