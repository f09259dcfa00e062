#!/usr/bin/env bash
# The Python package as a user installs it, against C libraries installed by CMake. No network.
#
#   cmake --install build --prefix PREFIX && tests/install/check_python.sh PREFIX
#
# In a temporary folder: a fresh virtual environment (python3 -m venv --system-site-packages, for
# Debian's numpy), `pip install --no-index --no-build-isolation` of the repository's python/ folder
# into it, then from another folder, with SPECSEG_LIB / PYTHONPATH / LD_LIBRARY_PATH unset:
#   1. the C libraries in the venv's own prefix (copied from PREFIX, same lib/ sub-folder, as
#      `cmake --install build --prefix VENV` puts them): found without any setting;
#   2. the libraries taken out of the venv: the import fails with an ImportError listing the
#      folders tried (unless the loader's own path has a libspecseg, which is reported);
#   3. SPECSEG_LIB=PREFIX/<libdir> (the folder) and SPECSEG_LIB=.../libspecseg.so (the file).
# Each run prints specseg.__version__, checks it against library_version() and PREFIX's version.h,
# and makes a smoke call (read_mesh of a small OFF written here, eigs, geodesic, render when the
# render library is there). Exit 0 on success, 1 with a message on the first failure.
# PYTHON (default /usr/bin/python3) is the interpreter the venv is made from.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PY=${PYTHON:-/usr/bin/python3}

fail() { echo "FAIL: $*" >&2; exit 1; }

[ $# -eq 1 ] || { echo "usage: $0 PREFIX   (where cmake --install put the C libraries)" >&2; exit 1; }
[ -d "$1" ] || fail "$1 is not a folder"
PREFIX=$(cd "$1" && pwd)

# where CMake put the libraries: lib, lib/<multiarch> (GNUInstallDirs on Debian under /usr) or lib64
LIBREL=""
MULTIARCH=$("$PY" -c "import sysconfig; print(sysconfig.get_config_var('MULTIARCH') or '')" 2>/dev/null)
for d in lib ${MULTIARCH:+lib/$MULTIARCH} lib64; do
  if compgen -G "$PREFIX/$d/libspecseg.so*" >/dev/null; then LIBREL=$d; break; fi
done
[ -n "$LIBREL" ] || fail "no libspecseg.so* in $PREFIX/lib, $PREFIX/lib/$MULTIARCH or $PREFIX/lib64 (run cmake --install build --prefix $PREFIX)"
LIBDIR="$PREFIX/$LIBREL"
HEADER="$PREFIX/include/specseg/version.h"
[ -f "$HEADER" ] || fail "$HEADER not found (an incomplete install?)"
HVER=$(sed -n 's/^#define SPECSEG_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\).*/\2/p' "$HEADER" | paste -sd.)
echo "C libraries: $LIBDIR (version.h: $HVER)"

# what the offline install needs (Debian: python3-venv python3-numpy python3-setuptools python3-wheel)
"$PY" - <<'EOF' || fail "$PY lacks what an offline install needs (Debian packages python3-venv python3-numpy python3-setuptools python3-wheel)"
import sys
missing = []
for mod in ("venv", "ensurepip", "numpy", "setuptools", "wheel"):
    try:
        __import__(mod)
    except ImportError:
        missing.append(mod)
import setuptools
if int(setuptools.__version__.split(".")[0]) < 61:
    missing.append("setuptools >= 61 (has %s)" % setuptools.__version__)
if missing:
    print("missing: " + ", ".join(missing), file=sys.stderr)
    sys.exit(1)
EOF

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
VENV="$WORK/venv"

# a copy of python/: pip builds in the source folder (build/, specseg.egg-info), which would leave
# files in the checkout
mkdir -p "$WORK/src"
cp -r "$ROOT/python/." "$WORK/src/"
rm -rf "$WORK/src/build" "$WORK/src"/*.egg-info
find "$WORK/src" -name __pycache__ -type d -prune -exec rm -rf {} +

"$PY" -m venv --system-site-packages "$VENV" >"$WORK/venv.log" 2>&1 || { cat "$WORK/venv.log" >&2; fail "$PY -m venv"; }
if ! env -u PYTHONPATH "$VENV/bin/python" -m pip install --no-index --no-build-isolation "$WORK/src" >"$WORK/pip.log" 2>&1; then
  tail -n 30 "$WORK/pip.log" >&2
  fail "pip install --no-index --no-build-isolation python/"
fi
echo "pip: $(tail -n 1 "$WORK/pip.log")"
SITE=$("$VENV/bin/python" -c "import sysconfig; print(sysconfig.get_paths()['purelib'])")
[ -f "$SITE/specseg/__init__.py" ] || fail "pip did not put specseg into $SITE"

# a small closed mesh (octahedron) as a user's input
RUN="$WORK/run"
mkdir -p "$RUN"
cat >"$RUN/octahedron.off" <<'EOF'
OFF
6 8 0
1 0 0
-1 0 0
0 1 0
0 -1 0
0 0 1
0 0 -1
3 0 2 4
3 2 1 4
3 1 3 4
3 3 0 4
3 2 0 5
3 1 2 5
3 3 1 5
3 0 3 5
EOF

# an ASan build of the libraries can only be loaded with the ASan runtime first
PRELOAD=()
if ldd "$(ls "$LIBDIR"/libspecseg.so* | head -n 1)" 2>/dev/null | grep -q libasan; then
  ASAN_RT=$(gcc -print-file-name=libasan.so)
  [ -f "$ASAN_RT" ] || fail "the libraries are an ASan build and no libasan.so can be preloaded"
  PRELOAD=(LD_PRELOAD="$ASAN_RT" ASAN_OPTIONS=detect_leaks=0)
fi

SMOKE='
import os, sys
import numpy as np
import specseg
want_dir, hver, site = sys.argv[1], sys.argv[2], sys.argv[3]
print("  specseg", specseg.__version__, "from", os.path.dirname(specseg.__file__))
print("  library", specseg.library_path, "version", specseg.library_version(), "render", specseg.render_library_path)
def fail(msg):
    print("  " + msg, file=sys.stderr)
    sys.exit(1)
if os.path.realpath(os.path.dirname(specseg.__file__)) != os.path.realpath(os.path.join(site, "specseg")):
    fail("imported specseg from %s, not the installed %s" % (specseg.__file__, site))
if os.path.realpath(os.path.dirname(specseg.library_path)) != os.path.realpath(want_dir):
    fail("library loaded from %s, expected %s" % (specseg.library_path, want_dir))
if specseg.__version__ != hver or specseg.library_version() != hver:
    fail("versions differ: package %s, library %s, version.h %s" % (specseg.__version__, specseg.library_version(), hver))
V, F = specseg.read_mesh("octahedron.off")
if V.shape != (6, 3) or F.shape != (8, 3):
    fail("read_mesh: shapes %s %s" % (V.shape, F.shape))
ev, X = specseg.eigs(V, F, 3)
if not (abs(ev[0]) < 1e-10 and ev[1] > 0 and X.shape == (6, 3)):
    fail("eigs: %s" % ev)
d = specseg.geodesic(V, F, [0])
if not (d[0] == 0 and np.isfinite(d).all() and abs(d[1] - d.max()) < 1e-12):
    fail("geodesic: %s" % d)
try:
    specseg.geodesic(V, F, [2 ** 32])
    fail("geodesic accepted source 2**32")
except ValueError:
    pass
if specseg.render_library_path is None:
    fail("the render library beside %s was not loaded" % specseg.library_path)
img = specseg.render(V, F, size=(32, 24))
if img.shape != (24, 32, 3) or not (img != 255).any():
    fail("render: %s" % (img.shape,))
print("  smoke: eigs %s, geodesic max %.4f, render %s" % (np.round(ev, 4).tolist(), d.max(), img.shape))
'

run_py() {  # run_py SPECSEG_LIB-or-empty ARGS... : the venv python in $RUN, nothing else set
  local lib=$1
  shift
  (cd "$RUN" && env -u PYTHONPATH -u PYTHONHOME -u LD_LIBRARY_PATH -u SPECSEG_LIB ${lib:+SPECSEG_LIB="$lib"} \
    "${PRELOAD[@]}" "$VENV/bin/python" "$@")
}

# 1. the C libraries in the venv's prefix, as `cmake --install build --prefix "$VENV"` puts them
mkdir -p "$VENV/$LIBREL"
cp -P "$LIBDIR"/libspecseg*.so* "$VENV/$LIBREL/"
echo "1. libraries in the venv prefix ($VENV/$LIBREL), nothing set:"
run_py "" -c "$SMOKE" "$VENV/$LIBREL" "$HVER" "$SITE" || fail "import / smoke call with the libraries in the venv prefix"

# 2. without them: a clear ImportError (or the loader's own path has a copy)
rm -f "$VENV/$LIBREL"/libspecseg*.so*
echo "2. no libraries in the venv prefix, nothing set:"
if run_py "" -c "import specseg; print(specseg.library_path)" >"$WORK/none.out" 2>"$WORK/none.err"; then
  echo "  note: found through the loader's search path: $(cat "$WORK/none.out")"
else
  grep -q "ImportError: specseg: cannot load the C library" "$WORK/none.err" && grep -q "$VENV/lib" "$WORK/none.err" \
    || { cat "$WORK/none.err" >&2; fail "no library: expected an ImportError listing the venv's lib folder"; }
  echo "  ImportError, tried:"
  grep '^  \[' "$WORK/none.err" | sed 's/^/  /'
fi

# 3. SPECSEG_LIB: the folder, then the file
echo "3a. SPECSEG_LIB=$LIBDIR:"
run_py "$LIBDIR" -c "$SMOKE" "$LIBDIR" "$HVER" "$SITE" || fail "import / smoke call with SPECSEG_LIB=$LIBDIR"
CORE=$(ls "$LIBDIR"/libspecseg.so "$LIBDIR"/libspecseg.so.* 2>/dev/null | head -n 1)
echo "3b. SPECSEG_LIB=$CORE:"
run_py "$CORE" -c "$SMOKE" "$LIBDIR" "$HVER" "$SITE" || fail "import / smoke call with SPECSEG_LIB=$CORE"

echo "OK: specseg $HVER installs offline and finds $LIBDIR"
exit 0
