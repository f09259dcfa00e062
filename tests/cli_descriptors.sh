#!/usr/bin/env bash
# specseg descriptors (WKS / HKS as .npy) and match --descriptors DX DY [--no-wks]: the shapes and
# normalisation of the arrays (numpy), equal to the Python binding's wks() / hks(), standard output;
# the WKS given back to match as one's own descriptors with --no-wks reproduces the default STD map;
# extra descriptors change it; and the usage / input errors. NumPy checks SKIP without python3-numpy.
# Usage: cli_descriptors.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
ROOT=$(cd "$(dirname "$0")/.." && pwd)

demo_outputs "$TMP/demo" "$TMP/demo.out" || bad "demo failed: $(tail -3 "$TMP/demo.out")"
X="$TMP/demo/humanoid_pose0.off"
Y="$TMP/demo/humanoid_pose2.off"
[ -s "$X" ] && [ -s "$Y" ] || { bad "the demo wrote no humanoids"; finish; }
NP=""
[ -n "$PY" ] && "$PY" -c "import numpy" 2> /dev/null && NP=$PY

# ---- descriptors ----
"$BIN" descriptors "$X" --wks -o "$TMP/wx.npy" > "$TMP/out" 2>&1 && ok || bad "descriptors --wks: $(cat "$TMP/out")"
grep -q "^WKS, 100 energies from 100 eigenpairs" "$TMP/out" && ok || bad "summary: $(cat "$TMP/out")"
"$BIN" descriptors "$Y" --wks -o "$TMP/wy.npy" > /dev/null 2>&1 || bad "descriptors --wks Y"
"$BIN" descriptors "$X" --hks -k 30 -n 16 -o "$TMP/hx.npy" > /dev/null 2>&1 && ok || bad "descriptors --hks"
"$BIN" descriptors "$X" --hks -k 30 -n 16 -o - > "$TMP/hs.npy" 2> "$TMP/err" && cmp -s "$TMP/hs.npy" "$TMP/hx.npy" &&
  grep -q -- "-> <stdout>" "$TMP/err" && ok || bad "descriptors -o -: not the same bytes, or no summary on stderr"
"$BIN" descriptors - --wks -k 20 -n 8 -o "$TMP/ws.npy" < "$X" > /dev/null 2>&1 && ok || bad "descriptors of standard input"
if [ -z "$NP" ]; then
  skip "numpy checks (no python3 with numpy)"
else
  LIB="$(dirname "$BIN")/libspecseg.so"
  ENVV=(SPECSEG_LIB="$LIB" PYTHONPATH="$ROOT/python" PYTHONDONTWRITEBYTECODE=1)
  if [ -f "$LIB" ] && ldd "$LIB" | grep -q libasan; then # python is not instrumented: preload the runtime
    ENVV+=(LD_PRELOAD="$(gcc -print-file-name=libasan.so)" ASAN_OPTIONS=detect_leaks=0)
  fi
  env "${ENVV[@]}" "$NP" - "$TMP" "$X" <<'PYEOF' && ok || bad "descriptor arrays (shapes, norms, binding)"
import sys
import numpy as np
t, X = sys.argv[1], sys.argv[2]
wx, hx = np.load(t + "/wx.npy"), np.load(t + "/hx.npy")
lines = [l for l in open(X).read().split("\n") if l.strip()]
nv = int(lines[1].split()[0])
assert wx.shape == (nv, 100) and wx.dtype == np.float64 and hx.shape == (nv, 16), (wx.shape, hx.shape)
assert np.isfinite(wx).all() and np.isfinite(hx).all() and (hx >= 0).all()
try:
    import specseg
except ImportError as e:  # no shared library beside the program: shapes only
    print("SKIP: binding comparison (%s)" % e)
    sys.exit(0)
V, F = specseg.read_mesh(X)
M = specseg.laplacian(V, F)[1]
for D in (wx, hx):
    assert np.allclose((M[:, None] * D * D).sum(0), 1, atol=1e-12), "columns not unit in L2(M)"
assert np.allclose(specseg.wks(V, F), wx, rtol=0, atol=1e-12), "wks() differs from the CLI"
assert np.allclose(specseg.hks(V, F, k=30, n=16), hx, rtol=0, atol=1e-12), "hks() differs from the CLI"
# the kept WKS columns (every 5th, as match sub-samples its own) and the coordinates as extra features
np.save(t + "/wx5.npy", wx[:, ::5])
np.save(t + "/wy5.npy", np.load(t + "/wy.npy")[:, ::5])
np.save(t + "/wy4.npy", np.load(t + "/wy.npy")[:, :4])
PYEOF
fi

# ---- match --descriptors ----
seq 0 1000 6000 > "$TMP/lm.txt"
"$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --probes std -o "$TMP/m0.txt" > /dev/null 2>&1 || bad "match std"
if [ -n "$NP" ] && [ -s "$TMP/wx5.npy" ]; then
  "$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --probes std --descriptors "$TMP/wx5.npy" "$TMP/wy5.npy" --no-wks \
    -o "$TMP/m1.txt" > "$TMP/out" 2>&1 && ok || bad "match --descriptors --no-wks: $(cat "$TMP/out")"
  grep -q "20 own descriptors (no WKS)" "$TMP/out" && ok || bad "match summary: $(cat "$TMP/out")"
  same=$(paste "$TMP/m0.txt" "$TMP/m1.txt" | awk '$1 == $2' | wc -l)
  [ "$same" -ge "$(($(wc -l < "$TMP/m0.txt") * 999 / 1000))" ] && ok ||
    bad "the WKS as own descriptors with --no-wks: only $same of $(wc -l < "$TMP/m0.txt") images as the default map"
  # beside the WKS they change the functional map (unrefined: the refinement may converge to the same map)
  "$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --probes std --no-refine -o "$TMP/m0n.txt" > /dev/null 2>&1 || bad "match std --no-refine"
  "$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --probes std --no-refine --descriptors="$TMP/wx5.npy" "$TMP/wy5.npy" \
    -o "$TMP/m2.txt" > /dev/null 2>&1 && ok || bad "match --descriptors=DX DY beside the WKS"
  cmp -s "$TMP/m0n.txt" "$TMP/m2.txt" && bad "descriptors beside the WKS left the map unchanged" || ok
  # from standard input
  "$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --probes std --descriptors - "$TMP/wy5.npy" --no-wks \
    -o "$TMP/m3.txt" < "$TMP/wx5.npy" > /dev/null 2>&1 && cmp -s "$TMP/m1.txt" "$TMP/m3.txt" && ok || bad "--descriptors - (stdin)"
  # errors: rows of the wrong shape, columns that do not correspond
  "$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --descriptors "$TMP/wx5.npy" "$TMP/hx.npy" -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"
  [ $? = 1 ] && grep -q "columns" "$TMP/err" && ok || bad "column mismatch: $(cat "$TMP/err")"
  "$BIN" descriptors "$TMP/demo/sphere.off" --hks -k 10 -n 4 -o "$TMP/s.npy" > /dev/null 2>&1 ||
    "$NP" -c "import numpy as np; np.save('$TMP/s.npy', np.zeros((10, 4)))"
  "$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --descriptors "$TMP/s.npy" "$TMP/wy4.npy" -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"
  [ $? = 1 ] && grep -q "s.npy: [0-9]* rows, but .* has [0-9]* vertices" "$TMP/err" && ok || bad "row mismatch: $(cat "$TMP/err")"
fi
"$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" --no-wks -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"
[ $? = 2 ] && grep -q -- "--no-wks needs --descriptors" "$TMP/err" && ok || bad "--no-wks alone: $(cat "$TMP/err")"
"$BIN" match "$X" "$Y" --landmarks "$TMP/lm.txt" -o "$TMP/m.txt" --descriptors "$TMP/wx.npy" > /dev/null 2> "$TMP/err"
[ $? = 2 ] && grep -q -- "--descriptors needs two values" "$TMP/err" && ok || bad "--descriptors with one file: $(cat "$TMP/err")"

# ---- usage errors ----
for args in "--wks" "--wks --hks -o D.npy" "-o D.npy" "--wks -o D.txt" "--wks -o D.npy -n 0" "--hks -o D.npy -k 2"; do
  # shellcheck disable=SC2086
  "$BIN" descriptors "$X" $args > /dev/null 2>&1
  [ $? = 2 ] && ok || bad "descriptors $args: not a usage error"
done
"$BIN" descriptors "$X" --wks -k 100000 -o "$TMP/d.npy" > /dev/null 2> "$TMP/err"
[ $? = 1 ] && grep -q "smaller than the number of vertices" "$TMP/err" && ok || bad "-k too large: $(cat "$TMP/err")"
finish
