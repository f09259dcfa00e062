"""Loading libspecseg.so and mirroring the C structs the binding passes (ctypes).

The mirrors below follow include/specseg/*.h field by field; at load time their sizes are compared
with the library's own (ss_struct_size), so a header change raises instead of corrupting memory.
"""
import ctypes as C
import glob
import os

import numpy as np


class SpecsegError(RuntimeError):
    """A library call failed: `status` is the ss_status name, the message is the library's ss_error."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status


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
                ("w_extra", C.c_double), ("extra_dcomm", C.c_int), ("descr_k", C.c_int)]


class ss_pairing_options(C.Structure):
    _fields_ = [("min_ratio", C.c_double), ("mutual", C.c_int), ("max_rel_energy", C.c_double),
                ("min_landmarks", C.c_int)]


class ss_match_options(C.Structure):
    _fields_ = [("probes", C.c_int), ("fmap", ss_fmap_match_options), ("seg", ss_segment_options),
                ("segment_profile", C.c_int), ("pairing", ss_pairing_options), ("refine", C.c_int),
                ("refine_w_lap", C.c_double), ("refine_w_descr", C.c_double),
                ("seg_descr_k", C.c_int)]


class ss_segment_pairs(C.Structure):
    _fields_ = [("n", C.c_int), ("sx", C.POINTER(C.c_int)), ("sy", C.POINTER(C.c_int)),
                ("energy", C.POINTER(C.c_double)), ("nx", C.c_int), ("ny", C.c_int)]


class ss_match_result(C.Structure):
    _fields_ = [("nX", C.c_int), ("map", C.POINTER(C.c_int)), ("kc", C.c_int), ("C", C.POINTER(C.c_double)),
                ("pairs", ss_segment_pairs), ("centerX", C.POINTER(C.c_int)), ("centerY", C.POINTER(C.c_int)),
                ("t_segment", C.c_double), ("t_eigs", C.c_double), ("t_pair", C.c_double), ("t_fmap", C.c_double),
                ("t_zoomout", C.c_double), ("t_total", C.c_double), ("refine_choice", C.c_int),
                ("refine_energy", C.c_double * 4), ("notes", C.c_char * 256)]


class ss_render_options(C.Structure):
    _fields_ = [("width", C.c_int), ("height", C.c_int), ("azimuth", C.c_double), ("elevation", C.c_double),
                ("background", C.c_ubyte * 3), ("supersample", C.c_int), ("margin", C.c_double),
                ("scale", C.c_double)]


class ss_render_scene(C.Structure):
    _fields_ = [("mesh", C.POINTER(ss_mesh)), ("vertex_rgb", C.POINTER(C.c_ubyte)),
                ("face_rgb", C.POINTER(C.c_ubyte)), ("scalar", C.POINTER(C.c_double)), ("isolines", C.c_int),
                ("scalar_min", C.c_double), ("scalar_max", C.c_double), ("isoline_rgb", C.c_ubyte * 3),
                ("nmarkers", C.c_int), ("markers", C.POINTER(C.c_double)), ("marker_rgb", C.POINTER(C.c_ubyte)),
                ("marker_radius", C.c_double)]


MIRRORS = [ss_error, ss_mesh, ss_sparse, ss_cmcf_options, ss_remesh_options, ss_segment_options, ss_segmentation,
           ss_fmap_match_options, ss_match_options, ss_segment_pairs, ss_match_result, ss_render_options,
           ss_render_scene]

# ---- finding and loading the library ----------------------------------------------------------


def _candidates():
    env = os.environ.get("SPECSEG_LIB")
    if env:
        yield env
        return
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.normpath(os.path.join(here, "..", ".."))  # python/specseg -> repository root
    yield os.path.join(root, "build", "libspecseg.so")
    # other build folders (build-asan, build-<name>), newest first
    for p in sorted(glob.glob(os.path.join(root, "build*", "libspecseg.so")), key=os.path.getmtime, reverse=True):
        yield p
    yield "libspecseg.so"  # the loader's search path (installed library, LD_LIBRARY_PATH)


def _load():
    errors = []
    for path in _candidates():
        if os.sep in path and not os.path.exists(path):
            errors.append("%s: not found" % path)
            continue
        try:
            core = C.CDLL(path)
            # the render library sits beside the core; its handle also resolves the core's symbols
            rpath = os.path.join(os.path.dirname(path), os.path.basename(path).replace("libspecseg", "libspecseg_render", 1))
            try:
                return C.CDLL(rpath), path
            except OSError:
                return core, path
        except OSError as e:
            hint = ""
            if "asan" in str(e).lower() or "ASan runtime" in str(e):
                hint = " (an AddressSanitizer build: run python with LD_PRELOAD=$(gcc -print-file-name=libasan.so))"
            errors.append("%s: %s%s" % (path, e, hint))
    raise ImportError("specseg: cannot load libspecseg.so (set SPECSEG_LIB to its path):\n  " + "\n  ".join(errors))


lib, lib_path = _load()

_i, _d, _p = C.c_int, C.c_double, C.c_void_p
_PM, _PE = C.POINTER(ss_mesh), C.POINTER(ss_error)
_PI, _PD = C.POINTER(C.c_int), C.POINTER(C.c_double)


def _sig(name, restype, *argtypes):
    f = getattr(lib, name, None)
    if f is None:
        return None
    f.restype = restype
    f.argtypes = list(argtypes)
    return f


# ss_struct_size may be missing in an older library: then the check is skipped
_struct_size = _sig("ss_struct_size", C.c_size_t, C.c_char_p)
_render_struct_size = _sig("ss_render_struct_size", C.c_size_t, C.c_char_p)
if _struct_size is not None:
    for _s in MIRRORS:
        _want = _struct_size(_s.__name__.encode())
        if not _want and _render_struct_size is not None:
            _want = _render_struct_size(_s.__name__.encode())
        if _want and _want != C.sizeof(_s):
            raise ImportError("specseg: struct %s is %d bytes in %s but %d in the Python mirror; update "
                              "python/specseg/_clib.py" % (_s.__name__, _want, lib_path, C.sizeof(_s)))

_sig("ss_status_name", C.c_char_p, _i)
_sig("ss_mesh_free", None, _PM)
_sig("ss_read_mesh", _i, C.c_char_p, _PM, _PE)
_sig("ss_write_mesh", _i, C.c_char_p, _PM, C.POINTER(C.c_ubyte), _PE)
_sig("ss_cotan_stiffness", _i, _PM, C.POINTER(ss_sparse), _PE)
_sig("ss_mass_lumped", _i, _PM, _i, _PD, _PE)
_sig("ss_sparse_free", None, C.POINTER(ss_sparse))
_sig("ss_mesh_eigs", _i, _PM, _i, _PD, _PD, _PE)
_sig("ss_cmcf_default_options", None, C.POINTER(ss_cmcf_options))
_sig("ss_cmcf_smooth", _i, _PM, C.POINTER(ss_cmcf_options), _PM, _PE)
_sig("ss_remesh_default_options", None, C.POINTER(ss_remesh_options))
_sig("ss_remesh", _i, _PM, C.POINTER(ss_remesh_options), _PM, _PE)
_sig("ss_segment_default_options", None, C.POINTER(ss_segment_options))
_sig("ss_segment", _i, _PM, C.POINTER(ss_segment_options), C.POINTER(ss_segmentation), _PE)
_sig("ss_segmentation_free", None, C.POINTER(ss_segmentation))
_sig("ss_geodesic_distances", _i, _PM, _i, _PI, _i, _d, _PD, _PE)
_sig("ss_map_geodesic_error", _i, _PM, _i, _PI, _PI, _PI, _PD, _PD, _PE)
_sig("ss_match_default_options", None, C.POINTER(ss_match_options))
_sig("ss_match", _i, _PM, _PM, _i, _PI, _PI, C.POINTER(ss_match_options), C.POINTER(ss_match_result), _PE)
_sig("ss_match_result_free", None, C.POINTER(ss_match_result))
_sig("ss_render_default_options", None, C.POINTER(ss_render_options))
_sig("ss_render_scene_init", None, C.POINTER(ss_render_scene), _PM)
_sig("ss_render", _i, C.POINTER(ss_render_scene), C.POINTER(ss_render_options), C.POINTER(C.c_ubyte), _PE)
_sig("ss_render_fit_scale", _d, _PM, C.POINTER(ss_render_options))
_sig("ss_write_png", _i, C.c_char_p, C.POINTER(C.c_ubyte), _i, _i, _PE)
_sig("ss_label_color", None, _i, C.c_ubyte * 3)
_sig("ss_segmentation_face_colors", _i, _PM, _PI, C.POINTER(C.c_ubyte), C.POINTER(C.c_ubyte), _PE)
_sig("ss_labels_align", _i, _PI, _PI, _i, _PE)


def has(name):
    """True when the loaded library exports `name`."""
    return getattr(lib, name, None) is not None


def check(status, err):
    """Raise SpecsegError with the library's message when a call failed."""
    if status != 0:
        name = lib.ss_status_name(status)
        raise SpecsegError(name.decode() if name else str(status), err.msg.decode(errors="replace"))


# ---- NumPy <-> C ------------------------------------------------------------------------------


def ptr(a, ctype):
    return a.ctypes.data_as(C.POINTER(ctype)) if a is not None else None


def as_mesh(V, F):
    """A borrowed ss_mesh over NumPy arrays; returns (mesh, V, F) — keep V and F alive while it is used."""
    V = np.ascontiguousarray(V, dtype=np.float64)
    F = np.ascontiguousarray(F, dtype=np.int32)
    if V.ndim != 2 or V.shape[1] != 3:
        raise ValueError("V must be an (n, 3) array of vertex coordinates")
    if F.ndim != 2 or F.shape[1] != 3:
        raise ValueError("F must be an (m, 3) array of triangle vertex indices")
    if F.size and (F.min() < 0 or F.max() >= V.shape[0]):
        raise ValueError("F has vertex indices outside 0..%d" % (V.shape[0] - 1))
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
