#!/usr/bin/env bash
# `specseg prepare` and prepared shapes (.sss) in `match` and `segment` on two poses of the built-in
# humanoid: the same outputs as from the meshes (landmark-free and with landmarks, one or both
# prepared, from standard input), a clear error for too few eigenpairs, for damaged, truncated and
# other-version files and for segmentation options other than the prepared ones; usage errors.
# Usage: cli_prepare.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
demo_outputs "$TMP/demo" || { bad "demo"; finish; }
A="$TMP/demo/humanoid_pose0.off"
B=$(ls "$TMP"/demo/humanoid_pose*.off | grep -v pose0 | head -1)
"$BIN" prepare "$A" -o "$TMP/a.sss" > "$TMP/out" 2>&1 && ok || bad "prepare A: $(cat "$TMP/out")"
grep -Eq '^[0-9]+ vertices, [0-9]+ segments, 150 eigenpairs, pairing signature -> .*a.sss \([0-9]+ bytes\)$' "$TMP/out" && ok ||
  bad "prepare summary: $(cat "$TMP/out")"
"$BIN" prepare "$B" -o "$TMP/b.sss" > "$TMP/out" 2>&1 && ok || bad "prepare B: $(cat "$TMP/out")"
head -c 14 "$TMP/a.sss" | grep -q '^specseg-shape ' && ok || bad "file tag"

# what the pipeline repairs internally is said when preparing, not again when matching the prepared
# shape; STD with landmarks segments nothing, so nothing is closed for it
awk 'NR == 2 { print $1, $2 - 1, $3; next } { print }' "$A" | sed '$d' > "$TMP/hole.off"
"$BIN" prepare "$TMP/hole.off" -o "$TMP/hole.sss" > /dev/null 2> "$TMP/err" && ok || bad "prepare holed: $(cat "$TMP/err")"
grep -q "^specseg: warning: .*hole.off: 1 hole (boundary loop) closed internally" "$TMP/err" && ok ||
  bad "prepare: no hole warning: $(cat "$TMP/err")"
printf '0\n500\n1000\n' > "$TMP/lmh.txt"
"$BIN" match "$TMP/hole.sss" "$TMP/b.sss" --landmarks "$TMP/lmh.txt" -o "$TMP/mh.txt" > /dev/null 2> "$TMP/err" &&
  ! grep -q "hole" "$TMP/err" && ok || bad "match prepared holed: $(cat "$TMP/err")"
"$BIN" match "$TMP/hole.off" "$B" --landmarks "$TMP/lmh.txt" --probes std --no-refine -o "$TMP/mh.txt" > /dev/null \
  2> "$TMP/err" && ! grep -q "hole" "$TMP/err" && ok || bad "match std holed: $(cat "$TMP/err")"
"$BIN" match "$TMP/hole.off" "$B" --landmarks "$TMP/lmh.txt" --no-refine -o "$TMP/mh.txt" > /dev/null 2> "$TMP/err" &&
  grep -q "hole.off: 1 hole (boundary loop) closed internally" "$TMP/err" && ok || bad "match diff holed: $(cat "$TMP/err")"

# match: the same map and pairs from meshes, prepared shapes, a mix, and standard input
"$BIN" match "$A" "$B" -o "$TMP/m_mesh.txt" --pairs "$TMP/p_mesh.txt" > "$TMP/out_mesh" 2>&1 && ok || bad "match meshes"
"$BIN" match "$TMP/a.sss" "$TMP/b.sss" -o "$TMP/m_sss.txt" --pairs "$TMP/p_sss.txt" > "$TMP/out_sss" 2>&1 && ok ||
  bad "match prepared: $(cat "$TMP/out_sss")"
cmp -s "$TMP/m_mesh.txt" "$TMP/m_sss.txt" && cmp -s "$TMP/p_mesh.txt" "$TMP/p_sss.txt" && ok || bad "landmark-free map differs"
[ "$(sed 's/ -> .*//' "$TMP/out_mesh")" = "$(sed 's/ -> .*//' "$TMP/out_sss")" ] && ok ||
  bad "summary differs: $(diff "$TMP/out_mesh" "$TMP/out_sss")"
"$BIN" match "$TMP/a.sss" "$B" -o "$TMP/m_mix.txt" > /dev/null 2>&1 && cmp -s "$TMP/m_mesh.txt" "$TMP/m_mix.txt" && ok ||
  bad "mixed mesh / prepared"
"$BIN" match - "$TMP/b.sss" -o "$TMP/m_std.txt" < "$TMP/a.sss" > /dev/null 2>&1 && cmp -s "$TMP/m_mesh.txt" "$TMP/m_std.txt" &&
  ok || bad "prepared shape on standard input"
printf '0\n500\n1000\n' > "$TMP/lm.txt"
for opts in "" "--no-refine --probes std" "--no-refine --segment-profile soft"; do
  # shellcheck disable=SC2086
  "$BIN" match "$A" "$B" --landmarks "$TMP/lm.txt" $opts -o "$TMP/l_mesh.txt" > /dev/null 2>&1 &&
    "$BIN" match "$TMP/a.sss" "$TMP/b.sss" --landmarks "$TMP/lm.txt" $opts -o "$TMP/l_sss.txt" --timings > /dev/null 2> "$TMP/t" &&
    cmp -s "$TMP/l_mesh.txt" "$TMP/l_sss.txt" && ok || bad "map with landmarks ($opts) differs"
  # --timings (the default match): nothing segmented or solved for prepared shapes
  if [ -z "$opts" ]; then
    grep -q '^timing: segment 0.000000' "$TMP/t" && grep -q '^timing: eigs 0.000000' "$TMP/t" && ok || bad "timings: $(cat "$TMP/t")"
  fi
done

# too few eigenpairs for the match asked for
"$BIN" prepare "$A" -k 60 -o "$TMP/a60.sss" > /dev/null 2>&1 && ok || bad "prepare -k 60"
"$BIN" match "$TMP/a60.sss" "$TMP/b.sss" -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q 'X (the first shape) was prepared with 60 eigenpairs but this match needs 110' "$TMP/err" && ok ||
  bad "too few eigenpairs: rc $rc $(cat "$TMP/err")"
"$BIN" match "$TMP/a.sss" "$TMP/b.sss" --zoomout 160 -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q 'needs 160' "$TMP/err" && ok || bad "--zoomout 160 on 150: rc $rc $(cat "$TMP/err")"
# a file prepared for the earlier default (110 eigenpairs): matched landmark-free, the map kept refined
# to 110 only (the further refinement to 150 needs more), and a note says so; --final-zoomout 0 is the
# same map without the note
"$BIN" prepare "$A" -k 110 -o "$TMP/a110.sss" > /dev/null 2>&1 && ok || bad "prepare -k 110"
"$BIN" match "$TMP/a110.sss" "$TMP/b.sss" -o "$TMP/x110.txt" > "$TMP/out" 2>&1; rc=$?
[ $rc -eq 0 ] && grep -q 'note: .*the shapes hold 110 eigenpairs, fewer than hyp_final_kmax 150: the map kept is refined to 110 only' "$TMP/out" && ok ||
  bad "110 eigenpairs, landmark-free: rc $rc $(cat "$TMP/out")"
"$BIN" match "$TMP/a110.sss" "$TMP/b.sss" --final-zoomout 0 -o "$TMP/x0.txt" > "$TMP/out" 2>&1 && ! grep -q hyp_final_kmax "$TMP/out" &&
  cmp -s "$TMP/x110.txt" "$TMP/x0.txt" && ok || bad "--final-zoomout 0: $(cat "$TMP/out")"
"$BIN" match "$TMP/a60.sss" "$TMP/b.sss" --landmarks "$TMP/lm.txt" --k 30 --zoomout 60 --descr-k 30 -o "$TMP/x.txt" \
  > /dev/null 2>&1 && ok || bad "a match that fits in 60 eigenpairs"

# segment: the same labels and centres
"$BIN" segment "$A" -o "$TMP/s_mesh.txt" --centers "$TMP/c_mesh.txt" > "$TMP/so_mesh" 2>&1 && ok || bad "segment mesh"
"$BIN" segment "$TMP/a.sss" -o "$TMP/s_sss.txt" --centers "$TMP/c_sss.txt" > "$TMP/so_sss" 2>&1 && ok || bad "segment prepared"
cmp -s "$TMP/s_mesh.txt" "$TMP/s_sss.txt" && cmp -s "$TMP/c_mesh.txt" "$TMP/c_sss.txt" &&
  [ "$(sed 's/ -> .*//' "$TMP/so_mesh")" = "$(sed 's/ -> .*//' "$TMP/so_sss")" ] && ok || bad "segment output differs"
"$BIN" segment "$TMP/a.sss" --faces 5000 -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q 'was prepared with --faces 15000' "$TMP/err" && ok || bad "segment --faces mismatch: $(cat "$TMP/err")"

# damaged, truncated, extended, other-version files: refused, never used
size=$(wc -c < "$TMP/a.sss")
cp "$TMP/a.sss" "$TMP/d.sss"
printf 'X' | dd of="$TMP/d.sss" bs=1 seek=$((size / 2)) conv=notrunc 2> /dev/null
"$BIN" match "$TMP/d.sss" "$TMP/b.sss" -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q 'd.sss: damaged prepared shape: checksum mismatch' "$TMP/err" && ok || bad "flipped byte: $(cat "$TMP/err")"
head -c $((size - 100)) "$TMP/a.sss" > "$TMP/t.sss"
"$BIN" segment "$TMP/t.sss" -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q 'truncated' "$TMP/err" && ok || bad "truncated: $(cat "$TMP/err")"
{ cat "$TMP/a.sss"; printf 'x'; } > "$TMP/l.sss"
"$BIN" segment "$TMP/l.sss" -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q 'longer than' "$TMP/err" && ok || bad "extended: $(cat "$TMP/err")"
sed '1s/^specseg-shape [0-9]* /specseg-shape 9 /' "$TMP/a.sss" > "$TMP/v.sss"
"$BIN" match "$TMP/v.sss" "$TMP/b.sss" -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q 'format version 9; this library .* reads version 3 only' "$TMP/err" && ok || bad "version: $(cat "$TMP/err")"
: > "$TMP/e.sss"
"$BIN" segment "$TMP/e.sss" -o "$TMP/x.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q 'not a specseg prepared-shape file' "$TMP/err" && ok || bad "empty .sss: $(cat "$TMP/err")"

# usage
"$BIN" prepare "$A" > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "prepare without -o"
"$BIN" prepare "$A" -o - > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "prepare -o -"
"$BIN" prepare "$A" -k 2 -o "$TMP/x.sss" > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "prepare -k 2"
"$BIN" prepare --help | grep -q '^usage: specseg prepare MESH -o SHAPE.sss' && ok || bad "prepare --help"
finish
