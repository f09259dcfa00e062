"""The Python package itself (issue 11 item 5): version, docstrings, input validation, library search.

usage: test_package.py
Needs `import specseg` to work (PYTHONPATH / SPECSEG_LIB as tests/cli_python.sh sets them) and no data
set: the meshes are built here. Library-search cases run in child pythons with their own SPECSEG_LIB.
Prints "N passed, N failed" like the C tests and exits 1 on any failure.
"""
import inspect
import os
import re
import shutil
import subprocess
import sys
import tempfile
import warnings

import numpy as np

import specseg
from specseg import _clib, _validate

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
passed = failed = 0


def check(cond, what):
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what, file=sys.stderr)


def raises(exc, fn, what, match=None):
    """fn() raises exc (with `match` in the message when given)."""
    try:
        fn()
    except exc as e:
        check(match is None or match in str(e), "%s: message %r lacks %r" % (what, str(e), match))
        return
    except Exception as e:  # noqa: BLE001 - report the wrong kind
        check(False, "%s: raised %s (%s) instead of %s" % (what, type(e).__name__, e, exc.__name__))
        return
    check(False, "%s: no %s raised" % (what, exc.__name__))


def icosahedron():
    t = (1 + 5 ** 0.5) / 2
    V = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
                  [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], float)
    F = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
                  [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
                  [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]], np.int32)
    return V, F


V, F = icosahedron()
n = V.shape[0]
BIG = 2 ** 32
print("library:", specseg.library_path, specseg.library_version(), "package:", specseg.__version__)

# ---- version: one Python place, equal to the header and to the library built from it ---------------
with open(os.path.join(ROOT, "include", "specseg", "version.h")) as f:
    header = f.read()
parts = [re.search(r"#define SPECSEG_VERSION_%s (\d+)" % p, header) for p in ("MAJOR", "MINOR", "PATCH")]
check(all(parts), "version.h defines SPECSEG_VERSION_MAJOR / MINOR / PATCH")
if all(parts):
    hv = ".".join(m.group(1) for m in parts)
    check(specseg.__version__ == hv, "__version__ %s equals version.h %s" % (specseg.__version__, hv))
check(specseg.library_version() == specseg.__version__,
      "library_version() %s equals __version__ %s (library and package from one source)"
      % (specseg.library_version(), specseg.__version__))
with open(os.path.join(ROOT, "python", "pyproject.toml")) as f:
    pyproject = f.read()
check('attr = "specseg._version.__version__"' in pyproject and not re.search(r'^version\s*=\s*["\']', pyproject, re.M),
      "pyproject.toml takes its version from specseg/_version.py")
check(_clib.SOVERSION == "%s.%s" % tuple(specseg.__version__.split(".")[:2]), "SOVERSION of a 0.x version")

# the mismatch warning (the check run again with another library version)
saved = _clib.library_version
try:
    for other, warned in (("0.3.0", True), ("1.2.0", True), (specseg.__version__.rsplit(".", 1)[0] + ".7", False)):
        _clib.library_version = lambda v=other: v
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            _clib._check_version()
        got = [x for x in w if issubclass(x.category, specseg.LibraryVersionWarning)]
        check(bool(got) == warned, "library %s vs package %s: warning %s" % (other, specseg.__version__, bool(got)))
        if got:
            check(other in str(got[0].message) and specseg.__version__ in str(got[0].message),
                  "the warning names both versions: %s" % got[0].message)
finally:
    _clib.library_version = saved

# ---- docstrings: every public callable, NumPy style ------------------------------------------------
public = set(specseg.__all__)
for name in dir(specseg):
    obj = getattr(specseg, name)
    if not name.startswith("_") and callable(obj) and getattr(obj, "__module__", "").startswith("specseg"):
        check(name in public, "public callable %s is in __all__" % name)
for name in specseg.__all__:
    check(hasattr(specseg, name), "__all__ entry %s exists" % name)
    obj = getattr(specseg, name, None)
    if not callable(obj):
        continue
    doc = inspect.getdoc(obj) or ""
    check(len(doc) > 40, "%s has a docstring" % name)
    if inspect.isfunction(obj):
        params = list(inspect.signature(obj).parameters)
        if params:
            sec = re.search(r"^Parameters\n-+\n(.*?)(?:^\w[\w ]*\n-+\n|\Z)", doc, re.S | re.M)
            check(sec is not None, "%s: Parameters section" % name)
            listed = set()
            for line in (sec.group(1) if sec else "").splitlines():
                m = re.match(r"^(\w[\w, ]*?) :", line)
                if m:
                    listed.update(p.strip() for p in m.group(1).split(","))
            for p in params:
                check(p in listed, "%s: parameter %s documented" % (name, p))
        check(re.search(r"^Returns\n-+\n", doc, re.M) is not None, "%s: Returns section" % name)
        if name not in ("library_version",):
            check(re.search(r"^Raises\n-+\n", doc, re.M) is not None, "%s: Raises section" % name)
    elif isinstance(obj, type) and issubclass(obj, tuple) and hasattr(obj, "_fields"):
        for fld in obj._fields:
            check(re.search(r"^%s\b.* :" % fld, doc, re.M) or re.search(r"\b%s\b.* :" % fld, doc),
                  "%s: field %s documented" % (name, fld))

# ---- the conversion helpers ------------------------------------------------------------------------
a32 = _validate.as_int32_array
imax, imin = 2 ** 31 - 1, -(2 ** 31)
check(a32([imin, imax], "x").tolist() == [imin, imax], "as_int32_array: the int32 limits pass")
raises(ValueError, lambda: a32([imax + 1], "x"), "as_int32_array: 2**31", "int32")
raises(ValueError, lambda: a32([imin - 1], "x"), "as_int32_array: -2**31 - 1")
raises(ValueError, lambda: a32(np.array([BIG], np.uint64), "x"), "as_int32_array: uint64")
raises(ValueError, lambda: a32(np.array([2 ** 64], dtype=object), "x"), "as_int32_array: beyond 64 bits", "x[0]")
raises(ValueError, lambda: a32([[0, 1], [2, BIG]], "x"), "as_int32_array: 2-D position named", "x[1, 1]")
raises(ValueError, lambda: a32([0.5], "x"), "as_int32_array: fractional", "integer")
raises(ValueError, lambda: a32([np.nan], "x"), "as_int32_array: NaN")
raises(ValueError, lambda: a32([3], "x", 0, 2), "as_int32_array: above hi", "0..2")
raises(TypeError, lambda: a32(np.array([True]), "x"), "as_int32_array: booleans")
raises(TypeError, lambda: a32(["1"], "x"), "as_int32_array: strings")
check(a32([2.0, 3.0], "x").dtype == np.int32, "as_int32_array: whole floats accepted")
check(a32(np.zeros((0, 3)), "x").shape == (0, 3), "as_int32_array: empty keeps its shape")
z = np.arange(6, dtype=np.int32).reshape(2, 3)
check(a32(z, "x") is z or np.shares_memory(a32(z, "x"), z), "as_int32_array: no copy of int32 input")
raises(ValueError, lambda: _validate.as_int32(BIG, "k"), "as_int32: 2**32", "int32")
raises(ValueError, lambda: _validate.as_int32(float("inf"), "k"), "as_int32: inf")
raises(TypeError, lambda: _validate.as_int32(True, "k"), "as_int32: bool")
raises(TypeError, lambda: _validate.as_int32("3", "k"), "as_int32: str")
check(_validate.as_int32(np.int64(7), "k") == 7 and _validate.as_int32(7.0, "k") == 7, "as_int32: numpy / whole float")
raises(ValueError, lambda: _validate.as_float(float("nan"), "dt"), "as_float: NaN", "dt")
raises(ValueError, lambda: _validate.as_float(float("inf"), "dt"), "as_float: inf")
check(_validate.as_float(float("inf"), "d", allow_inf=True) == float("inf"), "as_float: inf where allowed")
raises(ValueError, lambda: _validate.as_float(0.0, "dt", positive=True), "as_float: positive")
raises(TypeError, lambda: _validate.as_float("1", "dt"), "as_float: str")
raises(ValueError, lambda: _validate.as_uint8_array([256], "rgb"), "as_uint8_array: 256", "0..255")
raises(ValueError, lambda: _validate.as_uint8_array([-1], "rgb"), "as_uint8_array: -1")

# ---- the public functions refuse what would wrap --------------------------------------------------
raises(ValueError, lambda: specseg.geodesic(V, F, [BIG]), "geodesic: source 2**32 (used to compute source 0)",
       "sources")
raises(ValueError, lambda: specseg.geodesic(V, F, [n]), "geodesic: source n")
raises(ValueError, lambda: specseg.geodesic(V, F, [-1]), "geodesic: source -1")
raises(ValueError, lambda: specseg.geodesic(V, F, []), "geodesic: no source")
raises(ValueError, lambda: specseg.geodesic(V, F, [0], max_dist=float("nan")), "geodesic: max_dist NaN", "max_dist")
raises(ValueError, lambda: specseg.geodesic(V, F + BIG, [0]), "geodesic: face indices + 2**32", "F[0, 0]")
raises(ValueError, lambda: specseg.geodesic(V, np.array([[0, 1, BIG]]), [0]), "geodesic: face index 2**32")
d = specseg.geodesic(V, F, [0])
check(d[0] == 0 and np.isfinite(d).all() and d[1:].min() > 0, "geodesic: a valid call still works")
check(np.array_equal(specseg.geodesic(V, F, [0], max_dist=float("inf")), d), "geodesic: max_dist inf = no limit")
check(np.array_equal(specseg.geodesic(V, F.astype(np.int64), np.array([0.0])), d), "geodesic: int64 F, float source")
ident = np.arange(n)
raises(ValueError, lambda: specseg.error(ident + BIG, V, F), "error: map + 2**32 (used to wrap to the identity)", "map")
raises(ValueError, lambda: specseg.error(ident, V, F, gt=ident + BIG), "error: gt + 2**32", "gt")
raises(ValueError, lambda: specseg.error(ident, V, F, sym=ident + BIG), "error: sym + 2**32", "sym")
raises(ValueError, lambda: specseg.error(ident, V, F, gt=ident[:-1]), "error: gt too short")
e0, m0 = specseg.error(ident, V, F)
check(m0 == 0 and not e0.any(), "error: identity map is exact")
raises(ValueError, lambda: specseg.eigs(V, F, BIG + 3), "eigs: k 2**32 + 3 (used to wrap to 3)", "k")
raises(ValueError, lambda: specseg.eigs(V, F, 2.5), "eigs: fractional k")
ev, X = specseg.eigs(V, F, 3)
check(ev.shape == (3,) and X.shape == (n, 3) and abs(ev[0]) < 1e-10, "eigs: a valid call still works")
raises(ValueError, lambda: specseg.smooth(V, F, dt=float("nan")), "smooth: dt NaN", "dt")
raises(ValueError, lambda: specseg.smooth(V, F, dt=float("inf")), "smooth: dt inf", "dt")
raises(ValueError, lambda: specseg.smooth(V, F, dt=-1.0), "smooth: dt negative", "dt")
raises(ValueError, lambda: specseg.smooth(V, F, steps=BIG), "smooth: steps 2**32 (used to wrap to 0)", "steps")
raises(ValueError, lambda: specseg.remesh(V, F, target_faces=BIG + 40), "remesh: target_faces 2**32 + 40",
       "target_faces")
raises(ValueError, lambda: specseg.segment(V, F, target_faces=BIG), "segment: target_faces 2**32")
raises(ValueError, lambda: specseg.segment(V, F, cleanup_rings=BIG), "segment: cleanup_rings 2**32")
raises(ValueError, lambda: specseg.match(V, F, V, F, [BIG]), "match: landmark 2**32", "landmarks")
raises(ValueError, lambda: specseg.match(V, F, V, F, [0, 1], landmarks_y=[0, BIG]), "match: landmark_y 2**32",
       "landmarks_y")
raises(ValueError, lambda: specseg.match(V, F, V, F, [0, 1], landmarks_y=[0]), "match: landmark counts differ")
raises(ValueError, lambda: specseg.match(V, F, V, F, [0], k=BIG + 20), "match: k 2**32 + 20", "k")
raises(ValueError, lambda: specseg.match(V, F, V, F, [0], zoomout=BIG), "match: zoomout 2**32", "zoomout")
raises(ValueError, lambda: specseg.match(V, F, V, F, hypotheses=0), "match: hypotheses 0", "hypotheses")
raises(ValueError, lambda: specseg.match(V, F, V, F, hypotheses=17), "match: hypotheses 17", "hypotheses")
raises(ValueError, lambda: specseg.match(V, F, V, F, final_zoomout=-1), "match: final_zoomout -1", "final_zoomout")
raises(ValueError, lambda: specseg.match(V, F, V, F, zoomout_step=0), "match: zoomout_step 0", "zoomout_step")
raises(ValueError, lambda: specseg.match(V, F, V, F, zoomout_samples=BIG), "match: zoomout_samples 2**32",
       "zoomout_samples")
raises(ValueError, lambda: specseg.match(V, F, V, F, descr_k=2), "match: descr_k 2", "descr_k")
raises(ValueError, lambda: specseg.match(V, F, V, F, flip_by="z"), "match: flip_by z", "flip_by")
raises(ValueError, lambda: specseg.match(V, F, V, F, flip_by=["x"]), "match: flip_by a list", "flip_by")
raises(ValueError, lambda: specseg.write_mesh(os.devnull + ".off", V, F, rgb=np.full((n, 3), 256)),
       "write_mesh: colour 256", "rgb")
if specseg.render_library_path:
    raises(ValueError, lambda: specseg.label_colors([BIG]), "label_colors: 2**32", "labels")
    raises(ValueError, lambda: specseg.align_labels([0, BIG], [0, 1]), "align_labels: 2**32")
    raises(ValueError, lambda: specseg.render(V, F, size=(BIG + 16, 16)), "render: width 2**32 + 16", "width")
    raises(ValueError, lambda: specseg.render(V, F, size=(16, 16), view=(float("nan"), 0)), "render: NaN azimuth",
           "azimuth")
    raises(ValueError, lambda: specseg.render(V, F, size=(16, 16), view=(0, float("inf"))), "render: inf elevation")
    raises(ValueError, lambda: specseg.render(V, F, size=(16, 16), background=(256, 0, 0)),
           "render: background 256 (used to wrap to 0)", "background")
    raises(ValueError, lambda: specseg.render(V, F, size=(16, 16), supersample=BIG + 2), "render: supersample 2**32+2")
    raises(ValueError, lambda: specseg.render(V, F, size=(16, 16), labels=np.full(n, BIG)), "render: labels 2**32")
    raises(ValueError, lambda: specseg.render(V, F, size=(16, 16), vertex_rgb=np.full((n, 3), 300)),
           "render: vertex colour 300")
    raises(ValueError, lambda: specseg.render(V, F, size=(16, 16), markers=[[0, 0, np.nan]]), "render: NaN marker")
    raises(ValueError, lambda: specseg.render(V, F, size=(16, 16), scalar=V[:, 0], isolines=BIG),
           "render: isolines 2**32")
    raises(ValueError, lambda: specseg.write_png(os.devnull, np.full((2, 2, 3), 256)), "write_png: value 256")
    img = specseg.render(V, F, size=(24, 16), view=(30, 10), markers=V[:1])
    check(img.shape == (16, 24, 3) and (img != 255).any(), "render: a valid call still works")
    check(specseg.label_colors([0, 1, 0]).shape == (3, 3), "label_colors: a valid call still works")

# ---- library search -------------------------------------------------------------------------------


def child(code, env_lib, cwd):
    """Run `code` in a fresh python (same interpreter, PYTHONPATH and preloads) with SPECSEG_LIB=env_lib."""
    env = dict(os.environ)
    if env_lib is None:
        env.pop("SPECSEG_LIB", None)
    else:
        env["SPECSEG_LIB"] = env_lib
    env["PYTHONPATH"] = os.path.join(ROOT, "python")
    return subprocess.run([sys.executable, "-c", code], env=env, cwd=cwd, capture_output=True, text=True)


libdir = os.path.dirname(os.path.realpath(specseg.library_path))
tmp = tempfile.mkdtemp()
try:
    show = "import specseg; print(specseg.library_path); print(specseg.render_library_path)"
    r = child(show, libdir, tmp)
    lines = r.stdout.split()
    check(r.returncode == 0 and len(lines) == 2 and os.path.dirname(lines[0]) == libdir
          and os.path.dirname(lines[1]) == libdir,
          "SPECSEG_LIB=<folder>: core and render from that folder (%s %s)" % (r.stdout, r.stderr[-500:]))
    r = child(show, os.path.join(libdir, "libspecseg.so"), tmp)
    check(r.returncode == 0 and r.stdout.split()[:1] == [os.path.join(libdir, "libspecseg.so")],
          "SPECSEG_LIB=<file>: that file (%s)" % r.stderr[-500:])
    empty = os.path.join(tmp, "empty")
    os.mkdir(empty)
    r = child("import specseg", empty, tmp)
    check(r.returncode != 0 and "ImportError" in r.stderr and empty in r.stderr and "SPECSEG_LIB" in r.stderr,
          "SPECSEG_LIB=<folder without the library>: ImportError naming it (%s)" % r.stderr[-500:])
    r = child("import specseg", os.path.join(tmp, "missing", "libspecseg.so"), tmp)
    check(r.returncode != 0 and "not found" in r.stderr, "SPECSEG_LIB=<missing file>: ImportError")
    # a folder with the core only: everything but the render functions works
    core_only = os.path.join(tmp, "core")
    os.mkdir(core_only)
    for p in os.listdir(libdir):
        if re.match(r"libspecseg\.so(\.|$)", p):
            shutil.copy(os.path.join(libdir, p), os.path.join(core_only, p), follow_symlinks=True)
    code = ("import specseg, numpy as np\n"
            "V = np.array([[0,0,0],[1,0,0],[0,1,0],[0,0,1]], float); F = np.array([[0,2,1],[0,1,3],[0,3,2],[1,2,3]])\n"
            "print(specseg.render_library_path)\n"
            "print(specseg.geodesic(V, F, [0])[1])\n"
            "try:\n    specseg.render(V, F)\nexcept ImportError as e:\n    print('render:', e)\n")
    r = child(code, core_only, tmp)
    out = r.stdout.splitlines()
    check(r.returncode == 0 and out[:2] == ["None", "1.0"] and len(out) == 3 and "libspecseg_render" in out[2]
          and core_only in out[2], "core without render: geodesic works, render raises ImportError (%s %s)"
          % (r.stdout, r.stderr[-500:]))
    # from the checkout without SPECSEG_LIB: one of the repository's build folders
    r = child(show, None, tmp)
    got = os.path.dirname(r.stdout.split()[0]) if r.returncode == 0 and r.stdout.split() else None
    check(got is not None and os.path.realpath(got) in [os.path.realpath(d) for d in _clib._build_dirs(ROOT)],
          "no SPECSEG_LIB, run from the checkout: a build folder of the repository (%s %s)" % (got, r.stderr[-500:]))
    locs = _clib.search_locations()
    origins = [o for o, _, _ in locs]
    check(origins.index("package") < origins.index("source tree") < origins.index("prefix") < origins.index("loader"),
          "search order: package, source tree, prefixes, loader")
    check(any(v == os.path.join(sys.prefix, "lib") for _, k, v in locs if k == "dir") or
          os.path.realpath(os.path.join(sys.prefix, "lib")) in [os.path.realpath(v) for _, k, v in locs],
          "sys.prefix/lib is searched")
    check([o for o, _, _ in _clib.search_locations(libdir)] == ["SPECSEG_LIB"], "SPECSEG_LIB: nothing else searched")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
