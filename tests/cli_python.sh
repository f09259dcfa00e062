#!/usr/bin/env bash
# The Python binding (python/specseg) against the CLI on the same input (test_binding.py), and the
# package's own checks (test_package.py). $1: the specseg binary; the shared library is taken from
# the same build folder. Under an ASan build the library can only be
# loaded into python with the ASan runtime preloaded, which this script arranges; there the mesh is
# remeshed to 4,000 faces first (the comparisons hold on any closed mesh; FAUST's 13,776 faces made
# this the suite's longest test under the sanitizer).
set -u
BIN=$(realpath "$1")
BUILD=$(dirname "$BIN")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
LIB="$BUILD/libspecseg.so"
[ -f "$LIB" ] || { echo "FAIL: $LIB not found"; exit 1; }

# the system python with NumPy (Debian's python3-numpy), not a pyenv shim without it
PY=""
for p in /usr/bin/python3 python3; do
  if command -v "$p" >/dev/null 2>&1 && "$p" -c "import numpy" >/dev/null 2>&1; then PY=$p; break; fi
done
if [ -z "$PY" ]; then echo "SKIP: no python3 with numpy"; exit 77; fi

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

MESH=""
if [ -n "${SS_DATA_DIR:-}" ] && [ -f "$SS_DATA_DIR/faust/tr_reg_000.off" ]; then
  MESH="$SS_DATA_DIR/faust/tr_reg_000.off"
else
  "$BIN" demo -o "$WORK/demo" >/dev/null || { echo "FAIL: specseg demo"; exit 1; }
  MESH="$WORK/demo/humanoid_pose0.off"
fi

if ldd "$LIB" | grep -q libasan; then
  "$BIN" remesh "$MESH" --faces 4000 -o "$WORK/small.off" 2>/dev/null || { echo "FAIL: specseg remesh $MESH"; exit 1; }
  MESH="$WORK/small.off"
fi

ENVV=(PYTHONDONTWRITEBYTECODE=1 SPECSEG_LIB="$LIB" PYTHONPATH="$ROOT/python${PYTHONPATH:+:$PYTHONPATH}")
EXTRA=()  # e.g. --no-match to leave the two-shape pipeline out
if ldd "$LIB" | grep -q libasan; then
  ASAN_RT=$(gcc -print-file-name=libasan.so)
  if [ ! -f "$ASAN_RT" ]; then echo "SKIP: ASan build but no libasan.so to preload"; exit 77; fi
  # python itself is not instrumented: preload the runtime, ignore python's own leaks
  ENVV+=(LD_PRELOAD="$ASAN_RT" ASAN_OPTIONS=detect_leaks=0)
  echo "ASan build: preloading $ASAN_RT"
fi
rc=0
env "${ENVV[@]}" "$PY" "$ROOT/tests/python/test_binding.py" "$BIN" "$MESH" "$WORK" "${EXTRA[@]}" || rc=1
# the package itself: version, docstrings, input validation, library search (no data set needed)
echo "test_package.py:"
env "${ENVV[@]}" "$PY" "$ROOT/tests/python/test_package.py" || rc=1
exit $rc
