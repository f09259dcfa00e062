#!/usr/bin/env bash
# .npy wherever a vector file is read or written, chosen by the extension (and by the NumPy magic on
# standard input): segment labels / centres, geodesic distances, error values, match maps as (n, 1)
# int32 / float64; render --labels / --scalar / --map / --landmarks from .npy (the same pictures as from
# text), "F.npy:J" for a column of `eigs --evecs`, int64 labels, and clear errors for a matrix without
# a column and for float labels. NumPy checks use the system python3 with numpy (SKIP without).
# Usage: cli_npy.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

demo_outputs "$TMP/demo" "$TMP/demo.out" || bad "demo failed: $(tail -3 "$TMP/demo.out")"
M="$TMP/demo/humanoid_pose0.off"
M2="$TMP/demo/humanoid_pose2.off"
[ -s "$M" ] || { bad "the demo wrote no humanoid"; finish; }
NV=$(sed -n 2p "$M" | awk '{print $1}')
NP=""
[ -n "$PY" ] && "$PY" -c "import numpy" 2> /dev/null && NP=$PY

# ---- writers ----
"$BIN" segment "$M" -o "$TMP/l.npy" --centers "$TMP/c.npy" --faces 6000 > /dev/null 2>&1 && ok || bad "segment -o L.npy"
"$BIN" segment "$M" -o "$TMP/l.txt" --centers "$TMP/c.txt" --faces 6000 > /dev/null 2>&1 || bad "segment -o L.txt"
head -c 6 "$TMP/l.npy" | od -An -c | grep -q "N   U   M   P   Y" && ok || bad "labels .npy has no NumPy magic"
"$BIN" geodesic "$M" --source 0 -o "$TMP/d.npy" > /dev/null 2>&1 && ok || bad "geodesic -o D.npy"
"$BIN" geodesic "$M" --source 0 -o "$TMP/d.txt" > /dev/null 2>&1 || bad "geodesic -o D.txt"
seq 0 $((NV - 1)) > "$TMP/id.txt"
awk '{ print (NR % 5 == 0) ? 0 : $1 }' "$TMP/id.txt" > "$TMP/m.txt"
"$BIN" error "$TMP/m.txt" "$M" -o "$TMP/e.npy" > /dev/null 2>&1 && ok || bad "error -o E.npy"
"$BIN" error "$TMP/m.txt" "$M" -o "$TMP/e.txt" > /dev/null 2>&1 || bad "error -o E.txt"
if [ -z "$NP" ]; then
  skip "numpy checks (no python3 with numpy)"
else
  "$NP" - "$TMP" <<'PYEOF' && ok || bad "the .npy files differ from the text ones"
import sys, numpy as np
t = sys.argv[1]
l, c, d, e = (np.load(t + "/%s.npy" % k) for k in "lcde")
assert l.dtype == np.int32 and l.shape[1] == 1, (l.dtype, l.shape)
assert (l[:, 0] == np.loadtxt(t + "/l.txt", dtype=int)).all()
assert (c[:, 0] == np.loadtxt(t + "/c.txt", dtype=int)).all()
assert d.dtype == np.float64 and (d[:, 0] == np.loadtxt(t + "/d.txt")).all()
assert (e[:, 0] == np.loadtxt(t + "/e.txt")).all()
# for the readers below: int64 1-D labels, a map, landmarks (n, 2), a (n, 3) field
np.save(t + "/l64.npy", l[:, 0].astype(np.int64))
np.save(t + "/m.npy", np.loadtxt(t + "/m.txt", dtype=np.int64))
np.save(t + "/lm.npy", np.array([[0, 5], [7, 9]], np.int32))
np.save(t + "/f3.npy", np.stack([np.zeros_like(d[:, 0]), d[:, 0], -d[:, 0]], 1))
np.save(t + "/lf.npy", l[:, 0].astype(np.float64))
PYEOF
fi

# ---- readers: the same pictures and numbers as from text ----
R=(--size 120x160 --no-titles)
"$BIN" render "$M" --labels "$TMP/l.npy" "${R[@]}" -o "$TMP/a.png" > /dev/null 2>&1 && ok || bad "render --labels L.npy"
"$BIN" render "$M" --labels "$TMP/l.txt" "${R[@]}" -o "$TMP/b.png" > /dev/null 2>&1 || bad "render --labels L.txt"
cmp -s "$TMP/a.png" "$TMP/b.png" && ok || bad "labels from .npy and text draw differently"
"$BIN" render "$M" --labels - "${R[@]}" -o "$TMP/s.png" < "$TMP/l.npy" > /dev/null 2>&1
cmp -s "$TMP/s.png" "$TMP/b.png" && ok || bad "labels .npy through standard input"
"$BIN" render "$M" --scalar "$TMP/d.npy" "${R[@]}" -o "$TMP/a.png" > /dev/null 2>&1 && ok || bad "render --scalar D.npy"
"$BIN" render "$M" --scalar "$TMP/d.txt" "${R[@]}" -o "$TMP/b.png" > /dev/null 2>&1
cmp -s "$TMP/a.png" "$TMP/b.png" && ok || bad "a field from .npy and text draw differently"
"$BIN" render "$M" --labels "$TMP/c.npy" "${R[@]}" -o "$TMP/x.png" > /dev/null 2> "$TMP/err"
[ $? = 1 ] && grep -q "values, the mesh has" "$TMP/err" && ok || bad "short .npy labels: $(cat "$TMP/err")"
# eigs --evecs: one column by F.npy:J; the whole matrix is refused with a pointer to :J
"$BIN" eigs "$M" -k 3 --evecs "$TMP/ev.npy" > /dev/null 2>&1 || bad "eigs --evecs"
"$BIN" render "$M" --scalar "$TMP/ev.npy:1" "${R[@]}" -o "$TMP/f.png" > /dev/null 2>&1 && ok || bad "render --scalar EV.npy:1"
"$BIN" render "$M" --scalar "$TMP/ev.npy" "${R[@]}" -o "$TMP/x.png" > /dev/null 2> "$TMP/err"
[ $? = 1 ] && grep -q "ev.npy:J" "$TMP/err" && ok || bad "(n, 3) as a field: $(cat "$TMP/err")"
"$BIN" render "$M" --scalar "$TMP/ev.npy:3" "${R[@]}" -o "$TMP/x.png" > /dev/null 2> "$TMP/err"
[ $? = 1 ] && grep -q "column 3" "$TMP/err" && ok || bad "column out of range: $(cat "$TMP/err")"
if [ -n "$NP" ]; then
  "$BIN" render "$M" --scalar "$TMP/f3.npy:1" "${R[@]}" -o "$TMP/a.png" > /dev/null 2>&1 && ok || bad "--scalar F.npy:1"
  "$BIN" render "$M" --scalar "$TMP/d.txt" "${R[@]}" -o "$TMP/b.png" > /dev/null 2>&1
  cmp -s "$TMP/a.png" "$TMP/b.png" && ok || bad "column 1 of (n, 3) is not the field"
  "$BIN" render "$M" --labels "$TMP/l64.npy" "${R[@]}" -o "$TMP/a.png" > /dev/null 2>&1 && ok || bad "int64 labels"
  "$BIN" render "$M" --labels "$TMP/l.txt" "${R[@]}" -o "$TMP/b.png" > /dev/null 2>&1
  cmp -s "$TMP/a.png" "$TMP/b.png" && ok || bad "int64 labels draw differently"
  "$BIN" render "$M" --labels "$TMP/lf.npy" "${R[@]}" -o "$TMP/x.png" > /dev/null 2> "$TMP/err"
  [ $? = 1 ] && grep -q "dtype" "$TMP/err" && ok || bad "float labels: $(cat "$TMP/err")"
  "$BIN" error "$TMP/m.npy" "$M" > "$TMP/o1" 2>&1 && ok || bad "error MAP.npy"
  "$BIN" error "$TMP/m.txt" "$M" > "$TMP/o2" 2>&1
  cmp -s "$TMP/o1" "$TMP/o2" && ok || bad "error of MAP.npy and MAP.txt differ: $(cat "$TMP/o1") / $(cat "$TMP/o2")"
  printf '0 5\n7 9\n' > "$TMP/lm.txt"
  "$BIN" render "$M" "$M2" --landmarks "$TMP/lm.npy" "${R[@]}" -o "$TMP/a.png" > /dev/null 2>&1 && ok || bad "landmarks .npy"
  "$BIN" render "$M" "$M2" --landmarks "$TMP/lm.txt" "${R[@]}" -o "$TMP/b.png" > /dev/null 2>&1
  cmp -s "$TMP/a.png" "$TMP/b.png" && ok || bad "(n, 2) landmarks from .npy and text differ"
fi
"$BIN" segment --help | grep -q "NumPy" && ok || bad "--help does not mention .npy"
finish
