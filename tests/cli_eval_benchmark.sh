#!/usr/bin/env bash
# `specseg eval --benchmark` end to end on a small generated benchmark: the demo's humanoid in two
# poses, each remeshed on its own (different connectivity, as FAUST_r), ground-truth points carried by
# the nearest vertex (tests/data/eval/nearest_points.awk), a third shape that is the second with its
# vertices renumbered, a short .vts, stand-in mirror points, a mesh that is missing and one that is cut
# short, and an external maps folder made from our maps (one map perturbed, one with a wrong line
# count, one missing, one as .npy). Every number of summary.json and every scored row of pairs.csv is
# recomputed independently (tests/python/bench_check.py) from `specseg error` on the K-point files;
# warnings, resume, a cut pairs.csv, --json, shards + eval merge, curves.png and usage errors. (That our
# map is `specseg match X Y`'s: tests/cli_eval_benchmark_data.sh, on real data.)
# Usage: cli_eval_benchmark.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/lib_cli.sh"
. "$HERE/lib_bench.sh"
[ -n "$PY" ] || { skip "no python3 for the checks"; finish; }
check() { PYTHONDONTWRITEBYTECODE=1 "$PY" "$HERE/python/bench_check.py" "$@"; }

# usage errors (exit 2) and a folder that is not there (exit 1)
"$BIN" eval --benchmark > /dev/null 2>&1; [ $? = 2 ] && ok || bad "--benchmark without DIR: exit != 2"
"$BIN" eval --benchmark "$TMP" --landmarks gt:0 > /dev/null 2>&1; [ $? = 2 ] && ok || bad "--landmarks gt:0: exit != 2"
"$BIN" eval --benchmark "$TMP" --no-match > /dev/null 2>&1; [ $? = 2 ] && ok || bad "--no-match without --maps: exit != 2"
"$BIN" eval --benchmark "$TMP" --maps ext > /dev/null 2>&1; [ $? = 2 ] && ok || bad "--maps without =DIR: exit != 2"
"$BIN" eval --benchmark "$TMP/none" --out "$TMP/o0" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc = 1 ] && grep -q "^specseg: error: .*none: not a folder" "$TMP/err" && ok || bad "missing folder: rc $rc, $(cat "$TMP/err")"
"$BIN" eval --help | grep -q -- "--benchmark DIR" && ok || bad "eval --help does not document --benchmark"

# the benchmark folder
demo_outputs "$TMP/demo" || { bad "demo"; finish; }
B=$TMP/bench
mkdir -p "$B/corres"
"$BIN" remesh "$TMP/demo/humanoid_pose0.off" -o "$B/hum0.off" --faces 4000 > /dev/null 2>&1 &&
  "$BIN" remesh "$TMP/demo/humanoid_pose2.off" -o "$B/hum2.off" --faces 4000 > /dev/null 2>&1 || { bad "remesh"; finish; }
awk -v K=60 -f "$HERE/data/eval/nearest_points.awk" "$TMP/demo/humanoid_pose0.off" "$B/hum0.off" > "$B/corres/hum0.vts"
awk -v K=60 -f "$HERE/data/eval/nearest_points.awk" "$TMP/demo/humanoid_pose2.off" "$B/hum2.off" > "$TMP/hum2_60.vts"
# hum10: hum2 with its vertices in reverse order (the same points, renumbered)
NV2=$(sed -n 2p "$B/hum2.off" | cut -d' ' -f1)
awk -v n="$NV2" 'NR <= 2 { print; next } NR <= 2 + n { v[NR - 3] = $0; if (NR == 2 + n) for (i = n - 1; i >= 0; i--) print v[i]; next }
  { print 3, n - 1 - $2, n - 1 - $3, n - 1 - $4 }' "$B/hum2.off" > "$B/hum10.off"
awk -v n="$NV2" '{ print n - $1 + 1 }' "$TMP/hum2_60.vts" > "$B/corres/hum10.vts"
head -n 50 "$TMP/hum2_60.vts" > "$B/corres/hum2.vts"     # a short file: pairs with hum2 use 50 points
# stand-in mirror points of hum10 (point k's mirror = the vertex of point (k + 7) mod 60)
awk '{ v[NR - 1] = $1 } END { for (k = 0; k < NR; k++) print v[(k + 7) % NR] }' "$B/corres/hum10.vts" > "$B/corres/hum10.sym.vts"
cp "$B/corres/hum0.vts" "$B/corres/ghost1.vts"           # a mesh that is missing
head -n 900 "$B/hum0.off" > "$B/hum5.off"                  # a mesh cut short
cp "$B/corres/hum0.vts" "$B/corres/hum5.vts"
printf 'hum0\thum2\nhum0 hum10\nhum10\thum0\n# a comment\nhum2 hum10\nhum0 ghost1\nhum5 hum0\n' > "$B/test_pairs.txt"

# 1. our maps
O=$TMP/out
"$BIN" eval --benchmark "$B" --out "$O" --cache "$TMP/cache" --jobs 2 --quiet > "$TMP/o1" 2> "$TMP/e1"; rc=$?
[ $rc = 0 ] && ok || bad "run 1: rc $rc: $(cat "$TMP/e1")"
grep -q "warning: .*hum5.off.*its 1 pair skipped" "$TMP/e1" && ok || bad "no warning for the cut mesh: $(cat "$TMP/e1")"
grep -q "warning: ghost1: no mesh file: its 1 pair skipped" "$TMP/e1" && ok || bad "no warning for the missing mesh"
grep -q "warning: .*hum2.vts: 50 points where the others have 60" "$TMP/e1" && ok || bad "no warning for the short .vts"
[ "$(grep -c "hum2.vts: 50 points" "$TMP/e1")" = 1 ] && ok || bad "the short .vts warned more than once"
for p in hum0__hum2 hum0__hum10 hum10__hum0 hum2__hum10; do
  [ "$(wc -l < "$O/maps/$p.txt")" = "$(sed -n 2p "$B/${p%%__*}.off" | cut -d' ' -f1)" ] && ok || bad "maps/$p.txt: not one line per vertex of X"
done
[ ! -e "$O/maps/hum0__ghost1.txt" ] && [ ! -e "$O/maps/hum5__hum0.txt" ] && ok || bad "maps written for skipped pairs"
ls "$TMP"/cache/hum0_*.sss > /dev/null 2>&1 && ok || bad "no cache entry for hum0"
grep -q "^specseg  *all  *6  *4  *2 " "$TMP/o1" && grep -q "^  *hum/ghost  *1  *0  *1 " "$TMP/o1" && ok || bad "table: $(cat "$TMP/o1")"

# 2. an external maps folder made from ours: one perturbed, one a line short, one missing, one .npy
E=$TMP/ext
mkdir -p "$E"
cp "$O"/maps/*.txt "$E/"
awk 'NR == FNR { if (FNR <= 10) hit[$1 - 1] = 1; next } { print ((FNR - 1) in hit) ? 0 : $1 }' "$B/corres/hum0.vts" \
  "$O/maps/hum0__hum10.txt" > "$E/hum0__hum10.txt"        # the first 10 points of hum0 sent to vertex 0
sed -i '$d' "$E/hum10__hum0.txt"                           # a wrong line count
rm "$E/hum2__hum10.txt"                                    # missing
cp "$E/hum0__hum2.txt" "$TMP/hum0__hum2.txt"
NPY=0
if "$PY" -c "import numpy" 2> /dev/null; then
  "$PY" -c "import numpy, sys; numpy.save(sys.argv[2], numpy.loadtxt(sys.argv[1], dtype=numpy.int64))" "$E/hum0__hum2.txt" \
    "$E/hum0__hum2.npy" && rm "$E/hum0__hum2.txt" && NPY=1
fi
"$BIN" eval --benchmark "$B" --out "$O" --cache "$TMP/cache" --jobs 2 --maps ext="$E" > "$TMP/o2" 2> "$TMP/e2"; rc=$?
[ $rc = 0 ] && ok || bad "run 2: rc $rc: $(cat "$TMP/e2")"
grep -q "eval: 6 new rows (4 kept)" "$TMP/e2" && ok || bad "run 2 did not keep our 4 scored rows: $(grep '^eval' "$TMP/e2")"
grep -q "warning: ext: hum10 -> hum0 skipped: .*hum10__hum0.txt: $(($(wc -l < "$O/maps/hum10__hum0.txt") - 1)) lines, but hum10 has" "$TMP/e2" &&
  ok || bad "no warning for the wrong line count: $(cat "$TMP/e2")"
grep -q "warning: ext: 1 of the 6 pairs have no map file (.*hum2__hum10.txt" "$TMP/e2" && ok || bad "no warning for the missing map"
# the recomputation: each scored map's K-point files through specseg error
REC=$TMP/rec.txt
: > "$REC"
for p in hum0__hum2 hum0__hum10 hum10__hum0 hum2__hum10; do recompute specseg "${p%%__*}" "${p##*__}" "$O/maps/$p.txt" "$B"; done
recompute ext hum0 hum2 "$TMP/hum0__hum2.txt" "$B"
recompute ext hum0 hum10 "$E/hum0__hum10.txt" "$B"
check "$O" "$REC" specseg:6:4:2,ext:6:2:4 > "$TMP/c2" && ok || bad "run 2 summary: $(cat "$TMP/c2")"
# scored by the same code: ext's copy of our map has our numbers; the perturbed one is worse
a=$(grep '^specseg,hum0,hum2,' "$O/pairs.csv" | cut -d, -f4-6) b=$(grep '^ext,hum0,hum2,' "$O/pairs.csv" | cut -d, -f4-6)
[ -n "$a" ] && [ "$a" = "$b" ] && ok || bad "ext's copy of our map (npy: $NPY) scored '$b', ours '$a'"
a=$(grep '^specseg,hum0,hum10,' "$O/pairs.csv" | cut -d, -f4) b=$(grep '^ext,hum0,hum10,' "$O/pairs.csv" | cut -d, -f4)
awk -v a="$a" -v b="$b" 'BEGIN { exit !(b > a) }' && ok || bad "the perturbed map is not worse: $b vs $a"
grep -q '^ext  *all  *6  *2  *4 ' "$TMP/o2" && ok || bad "no ext row in the table: $(cat "$TMP/o2")"
[ "$(png "$O/curves.png" size)" = "1600 1000" ] && ok || bad "curves.png size $(png "$O/curves.png" size)"
[ "$(png "$O/curves.png" chroma 31 99 180)" -gt 500 ] && [ "$(png "$O/curves.png" chroma 240 120 10)" -gt 500 ] && ok ||
  bad "curves.png lacks a method's curve"

# 3. resume: nothing new, pairs.csv unchanged; --json prints summary.json's text
cp "$O/pairs.csv" "$TMP/pairs.before"
"$BIN" eval --benchmark "$B" --out "$O" --cache "$TMP/cache" --jobs 2 --maps ext="$E" --json > "$TMP/o3" 2> "$TMP/e3"; rc=$?
[ $rc = 0 ] && grep -q "eval: 0 new rows (6 kept)" "$TMP/e3" && ok || bad "resume: rc $rc, $(grep '^eval' "$TMP/e3")"
cmp -s "$TMP/pairs.before" "$O/pairs.csv" && ok || bad "resume changed pairs.csv"
cmp -s "$TMP/o3" "$O/summary.json" && ok || bad "--json output differs from summary.json"
# a pairs.csv cut inside its last line: that row is computed again, the summary's numbers the same
head -c -40 "$TMP/pairs.before" > "$O/pairs.csv"
"$BIN" eval --benchmark "$B" --out "$O" --cache "$TMP/cache" --jobs 2 --maps ext="$E" --quiet > /dev/null 2> "$TMP/e4" && ok ||
  bad "cut pairs.csv: $(cat "$TMP/e4")"
check "$O" "$REC" specseg:6:4:2,ext:6:2:4 > "$TMP/c4" && ok || bad "after the cut: $(cat "$TMP/c4")"

# 4. shards + eval merge = one run (external maps only: --no-match; our maps as a method "ours")
M=(eval --benchmark "$B" --no-match --maps ours="$O/maps" --maps ext="$E" --pairs "$B/test_pairs.txt" --quiet)
"$BIN" "${M[@]}" --out "$TMP/u" > /dev/null 2>&1 &&
  "$BIN" "${M[@]}" --shard 1/2 --out "$TMP/s1" > /dev/null 2>&1 && "$BIN" "${M[@]}" --shard 2/2 --out "$TMP/s2" > /dev/null 2>&1 &&
  "$BIN" eval merge "$TMP/s1" "$TMP/s2/pairs.csv" --out "$TMP/m" > "$TMP/om" 2> "$TMP/em" && ok || bad "shards / merge: $(cat "$TMP/em")"
[ ! -e "$TMP/u/maps" ] && ok || bad "--no-match wrote maps/"
grep -q "merged 12 rows from 2 files" "$TMP/om" && ok || bad "merge: $(cat "$TMP/om")"
"$PY" -c "import json, sys; a, b = (json.load(open(p))['methods'] for p in sys.argv[1:]); sys.exit(a != b)" \
  "$TMP/u/summary.json" "$TMP/m/summary.json" && ok || bad "merged summary differs from the one-run summary"
[ "$("$PY" -c "import json; print(json.load(open('$TMP/m/summary.json'))['title'])")" = bench ] && ok || bad "merge lost the title"
# our maps scored as an external method give our numbers
a=$(grep '^specseg,' "$O/pairs.csv" | grep ',ok,' | cut -d, -f2-6 | sort) b=$(grep '^ours,' "$TMP/u/pairs.csv" | grep ',ok,' | cut -d, -f2-6 | sort)
[ -n "$a" ] && [ "$a" = "$b" ] && ok || bad "our maps scored as --maps differ from our rows"
# merging rows that disagree is refused
sed 's/^ext,hum0,hum2,0\.0/ext,hum0,hum2,0.9/' "$TMP/s1/pairs.csv" > "$TMP/bad.csv"
grep -q '^ext,hum0,hum2,0\.9' "$TMP/bad.csv" && { "$BIN" eval merge "$TMP/bad.csv" "$TMP/u/pairs.csv" --out "$TMP/m2" > /dev/null 2> "$TMP/err"
  [ $? = 1 ] && grep -q "twice with different results" "$TMP/err" && ok || bad "conflicting rows merged: $(cat "$TMP/err")"; }
# --landmarks into a folder of the landmark-free maps is refused
"$BIN" eval --benchmark "$B" --out "$O" --landmarks gt:3 --quiet > /dev/null 2> "$TMP/err"; rc=$?
[ $rc = 1 ] && grep -q "maps/ hold specseg's maps" "$TMP/err" && ok || bad "--landmarks into OUT of specseg: rc $rc, $(cat "$TMP/err")"
finish
