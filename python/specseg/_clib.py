"""Finding and loading the C libraries, and mirroring the C structs the binding passes (ctypes).

Where the libraries are looked for (the first core library that loads wins; the ImportError otherwise
lists every place tried):

1. ``$SPECSEG_LIB``: the core library itself (``.../libspecseg.so``) or a folder holding it. When set,
   nothing else is tried, so a wrong value is reported instead of silently using another copy.
2. Beside the package: ``specseg/lib/``, then the ``specseg/`` folder itself.
3. The build folders of the source tree, when the package is imported from a checkout
   (``python/specseg`` of the repository): ``build/``, then the other ``build*/`` folders, newest
   first. This comes before the prefixes so that a developer gets the library just built, not an
   older installed copy.
4. The install prefixes: ``sys.prefix`` and the prefix this package is installed under (e.g.
   ``~/.local`` for ``pip install --user``), each in ``lib/``, ``lib/<multiarch>`` and ``lib64/``,
   which is where ``cmake --install build --prefix PREFIX`` puts them.
5. The dynamic loader's own search (``LD_LIBRARY_PATH``, ``ld.so.cache``, the system folders).

In each folder ``libspecseg.so.<SOVERSION>`` (``0.2`` for the 0.2 series) is preferred to
``libspecseg.so``. The render library (``libspecseg_render``) is loaded from the same folder as the
core; when it is absent or cannot be loaded, everything else works and the render functions raise
ImportError saying why.

The struct mirrors below follow include/specseg/*.h field by field; at load time their sizes are
compared with the libraries' own (ss_struct_size, ss_render_struct_size), so a header change raises
ImportError instead of corrupting memory.
"""
import contextlib
import ctypes as C
import glob
import os
import platform
import sys
import sysconfig
import threading
import warnings

import numpy as np

from ._validate import as_float64_array, as_int32_array, INT32_MAX
from ._version import __version__


class SpecsegError(RuntimeError):
    """A call into the C library failed.

    The message is the library's own (``ss_error``), e.g. ``"mesh.off:12: face 7 has vertex index
    40 >= 38"``.

    Attributes
    ----------
    status : str
        The failure's ``ss_status_name``: ``"i/o error"``, ``"parse error"``, ``"invalid input"``,
        ``"out of memory"``, ``"numerical failure"`` or ``"unsupported"``.
    """

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status


class LibraryVersionWarning(UserWarning):
    """The loaded C library's major.minor version differs from the package's ``__version__``."""


# ---- struct mirrors ---------------------------------------------------------------------------

class ss_error(C.Structure):
    _fields_ = [("msg", C.c_char * 1024)]


class ss_mesh(C.Structure):
    _fields_ = [("nv", C.c_int), ("nf", C.c_int), ("V", C.POINTER(C.c_double)), ("F", C.POINTER(C.c_int))]


class ss_sparse(C.Structure):
    _fields_ = [("nrows", C.c_int), ("ncols", C.c_int), ("colptr", C.POINTER(C.c_int)),
                ("rowind", C.POINTER(C.c_int)), ("val", C.POINTER(C.c_double))]


class ss_cmcf_options(C.Structure):
    _fields_ = [("steps", C.c_int), ("dt", C.c_double), ("normalization", C.c_int),
                ("refactor_symbolic", C.c_int)]


class ss_remesh_options(C.Structure):
    _fields_ = [("target_faces", C.c_int), ("iterations", C.c_int), ("smooth_only_iterations", C.c_int),
                ("tolerance", C.c_double)]


class ss_segment_options(C.Structure):
    _fields_ = [("target_faces", C.c_int), ("no_streamline", C.c_int), ("cleanup_rings", C.c_int),
                ("n_eigs", C.c_int), ("cmcf_steps", C.c_int), ("cmcf_dt", C.c_double), ("sanitize", C.c_int)]


class ss_segmentation(C.Structure):
    _fields_ = [("nv", C.c_int), ("m", C.c_int), ("labels", C.POINTER(C.c_int)), ("centers", C.POINTER(C.c_int)),
                ("empty_segments", C.c_int), ("work", ss_mesh), ("psi", C.POINTER(C.c_int)),
                ("phi", C.POINTER(C.c_double)), ("lambda2", C.c_double), ("crit", C.POINTER(C.c_int)),
                ("crit_type", C.POINTER(C.c_byte)), ("ncrit_raw", C.c_int), ("work_labels", C.POINTER(C.c_int)),
                ("work_dist", C.POINTER(C.c_double)),
                ("t_read", C.c_double), ("t_smooth", C.c_double), ("t_remesh", C.c_double), ("t_psi", C.c_double),
                ("t_spectrum", C.c_double), ("t_critical", C.c_double), ("t_ivd", C.c_double),
                ("t_total", C.c_double)]


class ss_fmap_match_options(C.Structure):
    _fields_ = [("k", C.c_int), ("n_energies", C.c_int), ("sigma_factor", C.c_double), ("descr_step", C.c_int),
                ("w_descr", C.c_double), ("w_lap", C.c_double), ("w_dcomm", C.c_double), ("fix_constant", C.c_int),
                ("zoomout_kmax", C.c_int), ("zoomout_step", C.c_int),
                ("w_extra", C.c_double), ("extra_dcomm", C.c_int), ("descr_k", C.c_int),
                ("zoomout_samples", C.c_int), ("no_wks", C.c_int), ("w_orient", C.c_double)]


class ss_pairing_options(C.Structure):
    _fields_ = [("min_ratio", C.c_double), ("mutual", C.c_int), ("max_rel_energy", C.c_double),
                ("min_landmarks", C.c_int), ("min_map_share", C.c_double)]


class ss_autopair_options(C.Structure):
    _fields_ = [("descr_k", C.c_int), ("n_energies", C.c_int), ("sigma_factor", C.c_double),
                ("descr_radius", C.c_double), ("w_descr", C.c_double), ("w_geo", C.c_double),
                ("exact_max", C.c_int), ("orient_k", C.c_int), ("orient_descr_k", C.c_int),
                ("min_gap", C.c_double), ("min_mirror", C.c_double),
                ("recheck_margin", C.c_double), ("recheck_k", C.c_int), ("orient_keep", C.c_double),
                ("recheck_zoomout", C.c_int), ("recheck_samples", C.c_int), ("recheck_keep", C.c_double),
                ("alt_max", C.c_int), ("alt_gap", C.c_double), ("alt_margin", C.c_double),
                ("alt_min_score", C.c_double), ("hypotheses", C.c_int), ("hyp_gap", C.c_double),
                ("hyp_w_reversed", C.c_double),
                ("hyp_reversed_below", C.c_double), ("hyp_keep", C.c_double),
                ("hyp_min_margin", C.c_double), ("hyp_landmarks", C.c_int),
                ("hyp_landmark_tol", C.c_double), ("hyp_differ_tol", C.c_double),
                ("hyp_differ_share", C.c_double), ("hyp_min_orientation", C.c_double),
                ("hyp_confident_orientation", C.c_double),
                ("polish_rounds", C.c_int), ("polish_orient_tol", C.c_double),
                ("hyp_descriptor_map", C.c_int), ("hyp_descriptor_orient", C.c_double),
                ("hyp_w_map", C.c_double), ("hyp_max_map_energy", C.c_double),
                ("hyp_flip_orient", C.c_double), ("hyp_w_orientation", C.c_double),
                ("hyp_flip_side", C.c_int), ("hyp_final_kmax", C.c_int), ("hyp_reverse", C.c_int),
                ("hyp_final_polish", C.c_int), ("hyp_recheck_window", C.c_double),
                ("hyp_fit_scale", C.c_int), ("hyp_skip_tol", C.c_double),
                ("hyp_min_coverage", C.c_double)]


MAX_HYPOTHESES = 16  # SS_MAX_HYPOTHESES (match.h)


class ss_autopair_info(C.Structure):
    _fields_ = [("used", C.c_int), ("exact", C.c_int), ("energy", C.c_double), ("energy_mirror", C.c_double),
                ("energy_other", C.c_double), ("gap", C.c_double), ("mirror", C.c_double),
                ("mirror_other", C.c_double), ("confident", C.c_int), ("pairing_confident", C.c_int),
                ("cpu", C.c_double),
                ("rechecked", C.c_int), ("mirror_first", C.c_double), ("mirror_other_first", C.c_double),
                ("mirror_margin", C.c_double), ("alternatives", C.c_int), ("alternative", C.c_int),
                ("polished", C.c_int),
                ("hypotheses", C.c_int), ("hypothesis", C.c_int), ("hyp_descriptor", C.c_int),
                ("hyp_pair_energy", C.c_double * MAX_HYPOTHESES),
                ("hyp_orientation", C.c_double * MAX_HYPOTHESES), ("hyp_distortion", C.c_double * MAX_HYPOTHESES),
                ("hyp_energy", C.c_double * MAX_HYPOTHESES), ("hyp_map_energy", C.c_double * MAX_HYPOTHESES),
                ("hyp_orientation_min", C.c_double * MAX_HYPOTHESES), ("hyp_reversed", C.c_double * MAX_HYPOTHESES),
                ("hyp_landmarks", C.c_int), ("hyp_margin", C.c_double),
                ("hyp_differ", C.c_double * MAX_HYPOTHESES), ("hyp_flip_of", C.c_int * MAX_HYPOTHESES),
                ("hyp_flip_by_y", C.c_int * MAX_HYPOTHESES), ("hyp_from_y", C.c_int * MAX_HYPOTHESES),
                ("hyp_final_k", C.c_int), ("hyp_final_polished", C.c_int),
                ("hyp_rechecked", C.c_int), ("hyp_recheck_from", C.c_int),
                ("hyp_scale", C.c_double * MAX_HYPOTHESES), ("hyp_skipped_by", C.c_int * MAX_HYPOTHESES),
                ("coverage", C.c_double)]


class ss_match_options(C.Structure):
    _fields_ = [("probes", C.c_int), ("fmap", ss_fmap_match_options), ("seg", ss_segment_options),
                ("segment_profile", C.c_int), ("pairing", ss_pairing_options), ("refine", C.c_int),
                ("refine_w_lap", C.c_double), ("refine_w_descr", C.c_double),
                ("seg_descr_k", C.c_int), ("refine_single", C.c_int), ("autopair", ss_autopair_options),
                ("ndescr", C.c_int), ("descrX", C.POINTER(C.c_double)), ("descrY", C.POINTER(C.c_double)),
                ("std_pairs", C.c_int)]


class ss_map_polish_options(C.Structure):
    _fields_ = [("rounds", C.c_int), ("steps", C.c_int), ("w_surface_first", C.c_double),
                ("w_surface_last", C.c_double), ("w_map_first", C.c_double), ("w_map_last", C.c_double),
                ("neighbours", C.c_int), ("min_normal_dot", C.c_double), ("max_move", C.c_double), ("mend_mirrored", C.c_int)]


class ss_segment_pairs(C.Structure):
    _fields_ = [("n", C.c_int), ("sx", C.POINTER(C.c_int)), ("sy", C.POINTER(C.c_int)),
                ("energy", C.POINTER(C.c_double)), ("nx", C.c_int), ("ny", C.c_int)]


class ss_match_result(C.Structure):
    _fields_ = [("nX", C.c_int), ("map", C.POINTER(C.c_int)), ("kc", C.c_int), ("C", C.POINTER(C.c_double)),
                ("pairs", ss_segment_pairs), ("centerX", C.POINTER(C.c_int)), ("centerY", C.POINTER(C.c_int)),
                ("t_segment", C.c_double), ("t_eigs", C.c_double), ("t_pair", C.c_double), ("t_fmap", C.c_double),
                ("t_zoomout", C.c_double), ("t_total", C.c_double), ("refine_choice", C.c_int),
                ("refine_energy", C.c_double * 4), ("notes", C.c_char * 256), ("autopair", ss_autopair_info)]


class ss_shape_prep(C.Structure):
    _fields_ = [("mesh", C.POINTER(ss_mesh)), ("seg", ss_segmentation), ("kev", C.c_int),
                ("evals", C.POINTER(C.c_double)), ("evecs", C.POINTER(C.c_double)), ("M", C.POINTER(C.c_double)),
                ("area", C.c_double), ("t_segment", C.c_double), ("t_eigs", C.c_double),
                ("crit_fields", C.POINTER(C.c_double)), ("probe_cache", C.c_void_p), ("nprobe_cache", C.c_int)]


class ss_centre_signature(C.Structure):
    _fields_ = [("m", C.c_int), ("nd", C.c_int), ("centers", C.POINTER(C.c_int)), ("descr", C.POINTER(C.c_double)),
                ("D", C.POINTER(C.c_double)), ("volume_ratio", C.c_double), ("orient_sign", C.c_double),
                ("normals", C.POINTER(C.c_double)), ("prep", C.POINTER(ss_shape_prep)), ("sigma", C.POINTER(C.c_int)),
                ("sigma_score", C.c_double), ("probe_k", C.c_int), ("probe_descr_k", C.c_int), ("probe_p", C.c_int),
                ("probe_A", C.POINTER(C.c_double)), ("probe_P", C.POINTER(C.c_double))]


class ss_prepared_shape(C.Structure):
    _fields_ = [("mesh", ss_mesh), ("prep", ss_shape_prep), ("seg", ss_segment_options), ("has_signature", C.c_int),
                ("autopair", ss_autopair_options), ("sig", ss_centre_signature), ("has_proxy", C.c_int),
                ("proxy", ss_mesh), ("to_proxy", C.POINTER(C.c_int)), ("proxy_src", C.POINTER(C.c_int)),
                ("proxy_prep", ss_shape_prep)]


class ss_render_options(C.Structure):
    _fields_ = [("width", C.c_int), ("height", C.c_int), ("azimuth", C.c_double), ("elevation", C.c_double),
                ("background", C.c_ubyte * 3), ("supersample", C.c_int), ("margin", C.c_double),
                ("scale", C.c_double), ("up", C.c_int)]


class ss_render_scene(C.Structure):
    _fields_ = [("mesh", C.POINTER(ss_mesh)), ("vertex_rgb", C.POINTER(C.c_ubyte)),
                ("face_rgb", C.POINTER(C.c_ubyte)), ("scalar", C.POINTER(C.c_double)), ("isolines", C.c_int),
                ("scalar_min", C.c_double), ("scalar_max", C.c_double), ("isoline_rgb", C.c_ubyte * 3),
                ("nmarkers", C.c_int), ("markers", C.POINTER(C.c_double)), ("marker_rgb", C.POINTER(C.c_ubyte)),
                ("marker_radius", C.c_double)]



# checked against ss_struct_size (core) and ss_render_struct_size (render library) at load time
CORE_MIRRORS = [ss_error, ss_mesh, ss_sparse, ss_cmcf_options, ss_remesh_options, ss_segment_options,
                ss_segmentation, ss_fmap_match_options, ss_match_options, ss_segment_pairs, ss_match_result,
                ss_autopair_options, ss_shape_prep, ss_centre_signature, ss_prepared_shape, ss_map_polish_options]
RENDER_MIRRORS = [ss_render_options, ss_render_scene]


# ---- finding and loading the libraries ----------------------------------------------------------

CORE = "libspecseg"
RENDER = "libspecseg_render"
PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))


def _soversion(version):
    """The shared libraries' SOVERSION for a package version: MAJOR.MINOR in the 0.x series, else MAJOR."""
    major, minor = version.split(".")[:2]
    return "%s.%s" % (major, minor) if major == "0" else major


SOVERSION = _soversion(__version__)


def _file_names(stem):
    return ["%s.so.%s" % (stem, SOVERSION), "%s.so" % stem]


def _unique(items):
    seen, out = set(), []
    for x in items:
        if x and x not in seen:
            seen.add(x)
            out.append(x)
    return out


def _multiarch():
    """Debian-style multiarch folder names (x86_64-linux-gnu) for PREFIX/lib/<multiarch>."""
    names = [sysconfig.get_config_var("MULTIARCH")]
    if sys.platform.startswith("linux") and platform.machine():
        names.append("%s-linux-gnu" % platform.machine())
    return _unique(names)


def _package_prefix():
    """PREFIX when this package lives in PREFIX/lib*/python*/{site,dist}-packages/specseg, else None."""
    site = os.path.dirname(PACKAGE_DIR)
    if os.path.basename(site) not in ("site-packages", "dist-packages"):
        return None
    pydir = os.path.dirname(site)
    if not os.path.basename(pydir).startswith("python"):
        return None
    return os.path.dirname(os.path.dirname(pydir))


def _source_root():
    """The repository root when the package is imported from a checkout (ROOT/python/specseg), else None."""
    parent = os.path.dirname(PACKAGE_DIR)
    root = os.path.dirname(parent)
    if os.path.basename(parent) == "python" and os.path.isfile(os.path.join(root, "CMakeLists.txt")) \
            and os.path.isfile(os.path.join(root, "include", "specseg", "version.h")):
        return root
    return None


def _build_dirs(root):
    """ROOT/build, then the other ROOT/build*/ folders holding a core library, newest library first."""
    found = {}
    for p in glob.glob(os.path.join(root, "build*", CORE + ".so*")):
        d = os.path.dirname(p)
        found[d] = max(found.get(d, 0), os.path.getmtime(p))
    main = os.path.join(root, "build")
    rest = sorted((d for d in found if d != main), key=lambda d: found[d], reverse=True)
    return [main] + rest


def _prefix_lib_dirs(prefix):
    return [os.path.join(prefix, "lib")] + [os.path.join(prefix, "lib", m) for m in _multiarch()] + \
        [os.path.join(prefix, "lib64")]


def search_locations(env=None):
    """Where the core library is looked for, in order: a list of (origin, kind, value).

    kind is "file" (a path), "dir" (a folder to look into) or "name" (for the loader's own search).
    With `env` (the value of $SPECSEG_LIB) only that location.
    """
    if env:
        if os.path.isdir(env):
            return [("SPECSEG_LIB", "dir", os.path.abspath(env))]
        return [("SPECSEG_LIB", "file", os.path.abspath(env))]
    locs = [("package", "dir", os.path.join(PACKAGE_DIR, "lib")), ("package", "dir", PACKAGE_DIR)]
    root = _source_root()
    if root:
        locs += [("source tree", "dir", d) for d in _build_dirs(root)]
    for prefix in _unique([sys.prefix, _package_prefix()]):
        locs += [("prefix", "dir", d) for d in _prefix_lib_dirs(prefix)]
    locs += [("loader", "name", n) for n in _file_names(CORE)]
    seen, out = set(), []
    for origin, kind, value in locs:
        key = os.path.realpath(value) if kind != "name" else value
        if key not in seen:
            seen.add(key)
            out.append((origin, kind, value))
    return out


def _asan_hint(e):
    s = str(e)
    if "asan" in s.lower():
        return " (an AddressSanitizer build: run python with LD_PRELOAD=$(gcc -print-file-name=libasan.so))"
    return ""


def _open(path, tried, origin):
    try:
        return C.CDLL(path)
    except OSError as e:
        tried.append("[%s] %s: %s%s" % (origin, path, e, _asan_hint(e)))
        return None


class _DlInfo(C.Structure):
    _fields_ = [("dli_fname", C.c_char_p), ("dli_fbase", C.c_void_p), ("dli_sname", C.c_char_p),
                ("dli_saddr", C.c_void_p)]


def _loaded_file(handle, symbol):
    """The file a loaded library came from (dladdr on one of its symbols), or None."""
    try:
        dladdr = C.CDLL(None).dladdr  # glibc >= 2.34 has it in libc, older ones in libdl
    except (OSError, AttributeError):
        try:
            import ctypes.util
            dladdr = C.CDLL(ctypes.util.find_library("dl") or "libdl.so.2").dladdr
        except (OSError, AttributeError):
            return None
    dladdr.argtypes = [C.c_void_p, C.POINTER(_DlInfo)]
    dladdr.restype = C.c_int
    fn = getattr(handle, symbol, None)
    if fn is None:
        return None
    info = _DlInfo()
    if dladdr(C.cast(fn, C.c_void_p), C.byref(info)) and info.dli_fname:
        path = os.fsdecode(info.dli_fname)
        return path if os.path.isabs(path) else None
    return None


def _load_core():
    """(handle, path) of the first core library that loads; ImportError listing every attempt."""
    env = os.environ.get("SPECSEG_LIB")
    tried = []
    for origin, kind, value in search_locations(env):
        if kind == "name":
            h = _open(value, tried, origin)
            if h is not None:
                return h, _loaded_file(h, "ss_status_name") or value
        elif kind == "file":
            if not os.path.exists(value):
                tried.append("[%s] %s: not found" % (origin, value))
                continue
            h = _open(value, tried, origin)
            if h is not None:
                return h, value
        else:
            names = [os.path.join(value, n) for n in _file_names(CORE)]
            present = [p for p in names if os.path.exists(p)]
            if not present:
                tried.append("[%s] %s: no %s" % (origin, value, " or ".join(_file_names(CORE))))
            for p in present:
                h = _open(p, tried, origin)
                if h is not None:
                    return h, p
    head = "specseg: cannot load the C library %s (%s)" % (CORE, " or ".join(_file_names(CORE)))
    if env:
        head += "; SPECSEG_LIB is set, so only it was tried"
    raise ImportError("%s:\n  %s\nBuild and install the C library (cmake --install build --prefix %s), or set "
                      "SPECSEG_LIB to libspecseg.so or the folder holding it."
                      % (head, "\n  ".join(tried), sys.prefix))


def _load_render(core_path):
    """(handle, path, None) of the render library beside the core, or (None, None, why not)."""
    folder = os.path.dirname(core_path) if os.path.isabs(core_path) else None
    base = os.path.basename(core_path)
    suffix = base[len(CORE):] if base.startswith(CORE + ".so") else None
    names = _unique(([RENDER + suffix] if suffix else []) + _file_names(RENDER))
    tried = []
    if folder is None:  # the core came from the loader's search and dladdr could not say from where
        for n in names:
            h = _open(n, tried, "loader")
            if h is not None:
                return h, n, None
        return None, None, "; ".join(tried)
    present = [os.path.join(folder, n) for n in names if os.path.exists(os.path.join(folder, n))]
    if not present:
        return None, None, "no %s in %s (beside %s)" % (" or ".join(names), folder, base)
    for p in present:
        h = _open(p, tried, "beside the core")
        if h is not None:
            return h, p, None
    return None, None, "; ".join(tried)


lib, lib_path = _load_core()
render_lib, render_lib_path, render_error = _load_render(lib_path)

_i, _d, _p = C.c_int, C.c_double, C.c_void_p
_PM, _PE = C.POINTER(ss_mesh), C.POINTER(ss_error)
_PI, _PD = C.POINTER(C.c_int), C.POINTER(C.c_double)


def _sig(handle, name, restype, *argtypes):
    f = getattr(handle, name, None) if handle is not None else None
    if f is None:
        return None
    f.restype = restype
    f.argtypes = list(argtypes)
    return f


# ---- versions -----------------------------------------------------------------------------------

_ss_version = _sig(lib, "ss_version", C.c_char_p)


def library_version():
    """The loaded C library's version, as its ss_version() reports it ("MAJOR.MINOR.PATCH"); None for a
    library older than 0.2 (no ss_version)."""
    if _ss_version is None:
        return None
    return _ss_version().decode()


def _check_version():
    lv = library_version()
    if lv is None:
        warnings.warn("specseg: %s reports no version (no ss_version: older than 0.2) while the package is %s; "
                      "rebuild the C library from the same source" % (lib_path, __version__),
                      LibraryVersionWarning, stacklevel=2)
    elif lv.split(".")[:2] != __version__.split(".")[:2]:
        warnings.warn("specseg: the C library %s is version %s but the package is %s; major.minor differ, so "
                      "their interfaces may not match: install both from the same source"
                      % (lib_path, lv, __version__), LibraryVersionWarning, stacklevel=2)


_check_version()

# ---- the struct mirrors against the libraries' own sizes (skipped when a library cannot tell) ----


def _check_structs(handle, path, size_fn_name, mirrors):
    size_fn = _sig(handle, size_fn_name, C.c_size_t, C.c_char_p)
    if size_fn is None:
        return
    for s in mirrors:
        want = size_fn(s.__name__.encode())
        if want and want != C.sizeof(s):
            raise ImportError("specseg: struct %s is %d bytes in %s but %d in the Python mirror (specseg/_clib.py); "
                              "the package and the library do not match" % (s.__name__, want, path, C.sizeof(s)))


_check_structs(lib, lib_path, "ss_struct_size", CORE_MIRRORS)
if render_lib is not None:
    try:
        _check_structs(render_lib, render_lib_path, "ss_render_struct_size", RENDER_MIRRORS)
    except ImportError as e:  # the core still works: only the render functions are refused
        render_lib, render_error = None, str(e)

# ---- signatures ---------------------------------------------------------------------------------

_sig(lib, "ss_status_name", C.c_char_p, _i)
_sig(lib, "ss_mesh_free", None, _PM)
_sig(lib, "ss_read_mesh", _i, C.c_char_p, _PM, _PE)
_sig(lib, "ss_write_mesh", _i, C.c_char_p, _PM, C.POINTER(C.c_ubyte), _PE)
_sig(lib, "ss_cotan_stiffness", _i, _PM, C.POINTER(ss_sparse), _PE)
_sig(lib, "ss_mass_lumped", _i, _PM, _i, _PD, _PE)
_sig(lib, "ss_sparse_free", None, C.POINTER(ss_sparse))
_sig(lib, "ss_mesh_eigs", _i, _PM, _i, _PD, _PD, _PE)
_sig(lib, "ss_wks", _i, _i, _i, _PD, _PD, _PD, _i, _d, _PD, _PE)
_sig(lib, "ss_hks", _i, _i, _i, _PD, _PD, _PD, _i, _PD, _PE)
_sig(lib, "ss_cmcf_default_options", None, C.POINTER(ss_cmcf_options))
_sig(lib, "ss_cmcf_smooth", _i, _PM, C.POINTER(ss_cmcf_options), _PM, _PE)
_sig(lib, "ss_remesh_default_options", None, C.POINTER(ss_remesh_options))
_sig(lib, "ss_remesh", _i, _PM, C.POINTER(ss_remesh_options), _PM, _PE)
_sig(lib, "ss_segment_default_options", None, C.POINTER(ss_segment_options))
_sig(lib, "ss_segment", _i, _PM, C.POINTER(ss_segment_options), C.POINTER(ss_segmentation), _PE)
_sig(lib, "ss_segmentation_free", None, C.POINTER(ss_segmentation))
_sig(lib, "ss_geodesic_distances", _i, _PM, _i, _PI, _i, _d, _PD, _PE)
_sig(lib, "ss_map_geodesic_error", _i, _PM, _i, _PI, _PI, _PI, _PD, _PD, _PE)
_sig(lib, "ss_match_default_options", None, C.POINTER(ss_match_options))
_sig(lib, "ss_match", _i, _PM, _PM, _i, _PI, _PI, C.POINTER(ss_match_options), C.POINTER(ss_match_result), _PE)
_sig(lib, "ss_pair_auto", _i, _PM, _PM, C.POINTER(ss_match_options), C.POINTER(ss_segment_pairs),
     C.POINTER(C.POINTER(C.c_int)), C.POINTER(C.POINTER(C.c_int)), C.POINTER(ss_autopair_info), _PE)
_sig(lib, "ss_segment_pairs_free", None, C.POINTER(ss_segment_pairs))
_sig(lib, "ss_match_result_free", None, C.POINTER(ss_match_result))
_PS = C.POINTER(ss_prepared_shape)
_sig(lib, "ss_match_eigenpairs", _i, C.POINTER(ss_match_options), _i)
_sig(lib, "ss_prepared_shape_compute", _i, _PM, C.POINTER(ss_segment_options), _i, C.POINTER(ss_autopair_options), _PS,
     _PE)
_sig(lib, "ss_prepared_shape_write", _i, C.c_char_p, _PS, _PE)
_sig(lib, "ss_prepared_shape_read", _i, C.c_char_p, _PS, _PE)
_sig(lib, "ss_prepared_shape_free", None, _PS)
_sig(lib, "ss_shape_prep_compute_spectral", _i, _PM, _i, C.POINTER(ss_shape_prep), _PE)
_sig(lib, "ss_shape_prep_free", None, C.POINTER(ss_shape_prep))
_sig(lib, "ss_match_refine", _i, C.POINTER(ss_shape_prep), C.POINTER(ss_shape_prep), _PI, C.POINTER(ss_match_options), _PI,
     _PD, _PE)
_sig(lib, "ss_map_polish_default_options", None, C.POINTER(ss_map_polish_options))
_sig(lib, "ss_map_polish", _i, _PM, _PM, _PI, C.POINTER(ss_map_polish_options), _PI, _PE)
_sig(lib, "ss_match_prepared_shapes", _i, _PS, _PS, _i, _PI, _PI, C.POINTER(ss_match_options), C.POINTER(ss_match_result),
     C.c_char_p, C.c_size_t, _PE)
_sig(render_lib, "ss_render_default_options", None, C.POINTER(ss_render_options))
_sig(render_lib, "ss_render_scene_init", None, C.POINTER(ss_render_scene), _PM)
_sig(render_lib, "ss_render", _i, C.POINTER(ss_render_scene), C.POINTER(ss_render_options), C.POINTER(C.c_ubyte), _PE)
_sig(render_lib, "ss_render_fit_scale", _d, _PM, C.POINTER(ss_render_options))
_sig(render_lib, "ss_render_guess_up", _i, C.POINTER(_PM), _i)
_sig(render_lib, "ss_render_guess_up", _i, C.POINTER(_PM), _i)
_sig(render_lib, "ss_write_png", _i, C.c_char_p, C.POINTER(C.c_ubyte), _i, _i, _PE)
_sig(render_lib, "ss_label_color", None, _i, C.c_ubyte * 3)
_sig(render_lib, "ss_segmentation_face_colors", _i, _PM, _PI, C.POINTER(C.c_ubyte), C.POINTER(C.c_ubyte), _PE)
_sig(render_lib, "ss_labels_align", _i, _PI, _PI, _i, _PE)


# ---- OpenBLAS threads during calls --------------------------------------------------------------
# The library's parallelism is OpenMP (the shapes of a match side by side, fields, queries); OpenBLAS's
# own threads beside it only compete for the cores: a FAUST match from two meshes took 2.1-2.4 s wall /
# 4.2-4.6 s CPU with OpenBLAS's default threads against 1.4-1.6 s / 2.3-2.6 s with one. So, as the
# `specseg` program does, the library's compute calls run with OpenBLAS single-threaded, and the
# caller's setting is restored afterwards (numpy may share that OpenBLAS). OPENBLAS_NUM_THREADS in the
# environment wins; without OpenBLAS (another BLAS) nothing is changed.
_ob_get = getattr(lib, "openblas_get_num_threads", None)
_ob_set = getattr(lib, "openblas_set_num_threads", None)
if _ob_get is not None and _ob_set is not None:
    _ob_get.restype, _ob_get.argtypes = C.c_int, []
    _ob_set.restype, _ob_set.argtypes = None, [C.c_int]
_blas_lock = threading.Lock()
_blas_depth = 0  # calls in progress (several Python threads may call at once)
_blas_saved = 0  # the caller's thread count, restored when the last call ends


@contextlib.contextmanager
def one_blas_thread():
    """Run the body with the library's OpenBLAS single-threaded (see above); nests and is thread-safe."""
    global _blas_depth, _blas_saved
    if _ob_get is None or _ob_set is None or os.environ.get("OPENBLAS_NUM_THREADS"):
        yield
        return
    with _blas_lock:
        if _blas_depth == 0:
            _blas_saved = _ob_get()
            if _blas_saved > 1:
                _ob_set(1)
        _blas_depth += 1
    try:
        yield
    finally:
        with _blas_lock:
            _blas_depth -= 1
            if _blas_depth == 0 and _blas_saved > 1:
                _ob_set(_blas_saved)


def compute(fn, *args):
    """fn(*args) (a compute call of the library) with its OpenBLAS single-threaded: its status."""
    with one_blas_thread():
        return fn(*args)


def has(name):
    """True when the loaded core or render library exports `name`."""
    return getattr(lib, name, None) is not None or (render_lib is not None and getattr(render_lib, name, None) is not None)


def need_render(what):
    """The render library's handle; ImportError naming `what` needed it when it was not loaded."""
    if render_lib is None:
        raise ImportError("specseg.%s needs the render library %s, which could not be loaded: %s"
                          % (what, RENDER, render_error))
    return render_lib


def check(status, err):
    """Raise SpecsegError with the library's message when a call failed."""
    if status != 0:
        name = lib.ss_status_name(status)
        raise SpecsegError(name.decode() if name else str(status), err.msg.decode(errors="replace"))


# ---- NumPy <-> C --------------------------------------------------------------------------------


def ptr(a, ctype):
    return a.ctypes.data_as(C.POINTER(ctype)) if a is not None else None


def as_mesh(V, F):
    """A borrowed ss_mesh over NumPy arrays; returns (mesh, V, F) — keep V and F alive while it is used.

    V becomes C-contiguous float64 (n, 3), F C-contiguous int32 (m, 3) with every index in 0..n-1."""
    V = as_float64_array(V, "V")
    if V.ndim != 2 or V.shape[1] != 3:
        raise ValueError("V must be an (n, 3) array of vertex coordinates (got shape %s)" % (V.shape,))
    if V.shape[0] > INT32_MAX:
        raise ValueError("V has %d vertices; the library takes at most %d" % (V.shape[0], INT32_MAX))
    Fa = np.asarray(F)
    if Fa.ndim != 2 or Fa.shape[1] != 3:
        raise ValueError("F must be an (m, 3) array of triangle vertex indices (got shape %s)" % (Fa.shape,))
    if Fa.shape[0] > INT32_MAX:
        raise ValueError("F has %d faces; the library takes at most %d" % (Fa.shape[0], INT32_MAX))
    F = as_int32_array(Fa, "F", 0, V.shape[0] - 1)
    m = ss_mesh(V.shape[0], F.shape[0], ptr(V, C.c_double), ptr(F, C.c_int))
    return m, V, F


def take_mesh(m):
    """Copy a library-allocated ss_mesh into NumPy arrays and free it."""
    try:
        V = np.ctypeslib.as_array(m.V, shape=(m.nv, 3)).copy() if m.nv else np.zeros((0, 3))
        F = np.ctypeslib.as_array(m.F, shape=(m.nf, 3)).copy() if m.nf else np.zeros((0, 3), np.int32)
    finally:
        lib.ss_mesh_free(C.byref(m))
    return V, F


def copy_array(p, n, dtype):
    if n <= 0 or not p:
        return np.zeros(0, dtype)
    return np.ctypeslib.as_array(p, shape=(n,)).astype(dtype, copy=True)
