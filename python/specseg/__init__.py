"""specseg — coherent spectral segmentation and functional-map matching of triangle meshes.

A thin ctypes binding over the C library (libspecseg.so): NumPy arrays in and out, no copies of the
inputs, errors raised as SpecsegError carrying the library's message. Meshes are (V, F) pairs:
V float64 (n, 3), F int32 (m, 3), 0-based. The library is found through $SPECSEG_LIB, else
<repo>/build/libspecseg.so, else the newest <repo>/build*/libspecseg.so, else the loader's path.

    import specseg
    V, F = specseg.read_mesh("tr_reg_000.off")
    evals, evecs = specseg.eigs(V, F, k=10)
    seg = specseg.segment(V, F)                # seg.labels, seg.centers, seg.phi, ...
    d = specseg.geodesic(V, F, [412])          # exact geodesic distances
    img = specseg.render(V, F, labels=seg.labels)   # (H, W, 3) uint8
"""
import ctypes as C
import math
from collections import namedtuple

import numpy as np

from . import _clib
from ._clib import SpecsegError, check, lib

__all__ = ["SpecsegError", "read_mesh", "write_mesh", "laplacian", "eigs", "smooth", "remesh", "segment",
           "Segmentation", "geodesic", "match", "Match", "error", "render", "write_png", "label_colors", "align_labels",
           "library_path"]

library_path = _clib.lib_path


def _err():
    return _clib.ss_error()


def read_mesh(path):
    """Read an OFF / OBJ / PLY mesh. Returns (V, F)."""
    m, e = _clib.ss_mesh(), _err()
    check(lib.ss_read_mesh(str(path).encode(), C.byref(m), C.byref(e)), e)
    return _clib.take_mesh(m)


def write_mesh(path, V, F, rgb=None):
    """Write .off or .ply (by extension); rgb: optional (n, 3) uint8 per-vertex colours."""
    m, V, F = _clib.as_mesh(V, F)
    if rgb is not None:
        rgb = np.ascontiguousarray(rgb, dtype=np.uint8)
        if rgb.shape != (V.shape[0], 3):
            raise ValueError("rgb must be (n, 3) uint8")
    e = _err()
    check(lib.ss_write_mesh(str(path).encode(), C.byref(m), _clib.ptr(rgb, C.c_ubyte), C.byref(e)), e)


def laplacian(V, F, mass="barycentric"):
    """Cotangent stiffness W (symmetric, positive semi-definite) and lumped masses M.

    Returns (W, M): W a scipy.sparse.csc_matrix when SciPy is importable, else the CSC triple
    (indptr, indices, data); M a float64 vector."""
    kinds = {"barycentric": 0, "voronoi": 1}
    if mass not in kinds:
        raise ValueError("mass must be 'barycentric' or 'voronoi'")
    m, V, F = _clib.as_mesh(V, F)
    n = V.shape[0]
    W, e = _clib.ss_sparse(), _err()
    check(lib.ss_cotan_stiffness(C.byref(m), C.byref(W), C.byref(e)), e)
    try:
        nnz = W.colptr[W.ncols]
        indptr = _clib.copy_array(W.colptr, W.ncols + 1, np.int32)
        indices = _clib.copy_array(W.rowind, nnz, np.int32)
        data = _clib.copy_array(W.val, nnz, np.float64)
    finally:
        lib.ss_sparse_free(C.byref(W))
    M = np.zeros(n)
    check(lib.ss_mass_lumped(C.byref(m), kinds[mass], _clib.ptr(M, C.c_double), C.byref(e)), e)
    try:
        import scipy.sparse as sp
        return sp.csc_matrix((data, indices, indptr), shape=(n, n)), M
    except ImportError:
        return (indptr, indices, data), M


def eigs(V, F, k):
    """The k smallest Laplace-Beltrami eigenpairs (cotangent W, barycentric M; W φ = λ M φ).
    Returns (evals (k,), evecs (n, k)), evecs M-orthonormal."""
    m, V, F = _clib.as_mesh(V, F)
    n = V.shape[0]
    if not 1 <= k < n:
        raise ValueError("k must be between 1 and %d" % (n - 1))
    evals, evecs = np.zeros(k), np.zeros((k, n))  # column-major n x k == row-major k x n
    e = _err()
    check(lib.ss_mesh_eigs(C.byref(m), int(k), _clib.ptr(evals, C.c_double), _clib.ptr(evecs, C.c_double),
                           C.byref(e)), e)
    return evals, np.ascontiguousarray(evecs.T)


def smooth(V, F, steps=None, dt=None):
    """Conformalized mean curvature flow (paper §4.1). Returns the smoothed vertex array (same F)."""
    m, V, F = _clib.as_mesh(V, F)
    o = _clib.ss_cmcf_options()
    lib.ss_cmcf_default_options(C.byref(o))
    if steps is not None:
        o.steps = int(steps)
    if dt is not None:
        o.dt = float(dt)
    out, e = _clib.ss_mesh(), _err()
    check(lib.ss_cmcf_smooth(C.byref(m), C.byref(o), C.byref(out), C.byref(e)), e)
    V2, _ = _clib.take_mesh(out)
    return V2


def remesh(V, F, target_faces=15000):
    """Isotropic remeshing to about target_faces triangles. Returns (V2, F2)."""
    m, V, F = _clib.as_mesh(V, F)
    o = _clib.ss_remesh_options()
    lib.ss_remesh_default_options(C.byref(o))
    o.target_faces = int(target_faces)
    out, e = _clib.ss_mesh(), _err()
    check(lib.ss_remesh(C.byref(m), C.byref(o), C.byref(out), C.byref(e)), e)
    return _clib.take_mesh(out)


Segmentation = namedtuple("Segmentation", "labels centers m phi lambda2 work_V work_F psi crit work_labels "
                                          "ncrit_raw empty_segments")
Segmentation.__doc__ = """ss_segment's result: labels (n,) segment of each input vertex, centers (m,) input
vertex at each segment's centre, phi the Fiedler vector on the work mesh (work_V, work_F: smoothed and
remeshed shape), psi input -> work vertex, crit (m,) work vertex of each critical point."""


def segment(V, F, target_faces=None, no_streamline=False, cleanup_rings=None, sanitize=None):
    """Coherent segmentation (paper §4). Returns a Segmentation."""
    m, V, F = _clib.as_mesh(V, F)
    o = _clib.ss_segment_options()
    lib.ss_segment_default_options(C.byref(o))
    if target_faces is not None:
        o.target_faces = int(target_faces)
    o.no_streamline = 1 if no_streamline else 0
    if cleanup_rings is not None:
        o.cleanup_rings = int(cleanup_rings)
    if sanitize is not None:
        o.sanitize = 1 if sanitize else 0
    s, e = _clib.ss_segmentation(), _err()
    st = lib.ss_segment(C.byref(m), C.byref(o), C.byref(s), C.byref(e))
    try:
        check(st, e)
        cp = _clib.copy_array
        nw = s.work.nv
        wV = np.ctypeslib.as_array(s.work.V, shape=(nw, 3)).copy() if nw else np.zeros((0, 3))
        wF = np.ctypeslib.as_array(s.work.F, shape=(s.work.nf, 3)).copy() if s.work.nf else np.zeros((0, 3), np.int32)
        return Segmentation(labels=cp(s.labels, s.nv, np.int32), centers=cp(s.centers, s.m, np.int32), m=s.m,
                            phi=cp(s.phi, nw, np.float64), lambda2=s.lambda2, work_V=wV, work_F=wF,
                            psi=cp(s.psi, s.nv, np.int32), crit=cp(s.crit, s.m, np.int32),
                            work_labels=cp(s.work_labels, nw, np.int32), ncrit_raw=s.ncrit_raw,
                            empty_segments=s.empty_segments)
    finally:
        lib.ss_segmentation_free(C.byref(s))


_METHODS = {"exact": 0, "graph": 1, "edge": 2}


def geodesic(V, F, sources, method="exact", max_dist=None):
    """Distance from every vertex to the nearest source vertex: exact polyhedral geodesics (VTP) or
    the NPP22 / edge graph. Unreached vertices (or beyond max_dist) get inf."""
    if method not in _METHODS:
        raise ValueError("method must be one of %s" % ", ".join(_METHODS))
    m, V, F = _clib.as_mesh(V, F)
    src = np.ascontiguousarray(np.atleast_1d(sources), dtype=np.int32)
    if src.size == 0 or src.min() < 0 or src.max() >= V.shape[0]:
        raise ValueError("sources must be vertex indices in 0..%d" % (V.shape[0] - 1))
    d, e = np.zeros(V.shape[0]), _err()
    md = math.inf if max_dist is None else float(max_dist)
    check(lib.ss_geodesic_distances(C.byref(m), _METHODS[method], _clib.ptr(src, C.c_int), src.size, md,
                                    _clib.ptr(d, C.c_double), C.byref(e)), e)
    return d


def _ints(a, n, what, hi):
    a = np.ascontiguousarray(a, dtype=np.int32)
    if a.shape != (n,):
        raise ValueError("%s must have %d entries" % (what, n))
    if n and (a.min() < 0 or a.max() >= hi):
        raise ValueError("%s has entries outside 0..%d" % (what, hi - 1))
    return a


Match = namedtuple("Match", "map C pairs_x pairs_y centers_x centers_y")
Match.__doc__ = """ss_match's result: map (nX,) vertex of Y for each vertex of X; C the functional map
(functions on Y -> functions on X); the paired segments and their centre vertices."""

_PROBES = {"std": 0, "asa": 1, "diff": 2}


def match(VX, FX, VY, FY, landmarks, landmarks_y=None, probes="diff", k=None, zoomout=None, segment_profile=None):
    """Map X -> Y by the paper's pipeline (§6: segmentation of both shapes, segment pairing through
    the landmarks, functional map with STD / ASA / DIFF probes, optional ZoomOut). landmarks: vertex
    indices on X (and on Y unless landmarks_y is given). segment_profile: "indicator", "tent"
    (default) or "soft", the segments' probe functions (as `specseg match --segment-profile`).
    Returns a Match."""
    if not _clib.has("ss_match"):
        raise NotImplementedError("this libspecseg has no ss_match")
    if probes not in _PROBES:
        raise ValueError("probes must be std, asa or diff")
    profiles = {"indicator": 0, "tent": 1, "soft": 2}
    if segment_profile is not None and segment_profile not in profiles:
        raise ValueError("segment_profile must be indicator, tent or soft")
    mx, VX, FX = _clib.as_mesh(VX, FX)
    my, VY, FY = _clib.as_mesh(VY, FY)
    lx = np.ascontiguousarray(np.atleast_1d(landmarks), dtype=np.int32)
    ly = lx if landmarks_y is None else np.ascontiguousarray(np.atleast_1d(landmarks_y), dtype=np.int32)
    lx = _ints(lx, lx.size, "landmarks", VX.shape[0])
    ly = _ints(ly, lx.size, "landmarks_y", VY.shape[0])
    o = _clib.ss_match_options()
    lib.ss_match_default_options(C.byref(o))
    o.probes = _PROBES[probes]
    if k is not None:
        o.fmap.k = int(k)
    if zoomout is not None:
        o.fmap.zoomout_kmax = int(zoomout)
    if segment_profile is not None:
        o.segment_profile = profiles[segment_profile]
    r, e = _clib.ss_match_result(), _err()
    st = lib.ss_match(C.byref(mx), C.byref(my), lx.size, _clib.ptr(lx, C.c_int), _clib.ptr(ly, C.c_int),
                      C.byref(o), C.byref(r), C.byref(e))
    try:
        check(st, e)
        cp = _clib.copy_array
        Cm = cp(r.C, r.kc * r.kc, np.float64).reshape(r.kc, r.kc).T.copy() if r.kc else np.zeros((0, 0))
        return Match(map=cp(r.map, r.nX, np.int32), C=Cm, pairs_x=cp(r.pairs.sx, r.pairs.n, np.int32),
                     pairs_y=cp(r.pairs.sy, r.pairs.n, np.int32), centers_x=cp(r.centerX, r.pairs.n, np.int32),
                     centers_y=cp(r.centerY, r.pairs.n, np.int32))
    finally:
        lib.ss_match_result_free(C.byref(r))


def error(map, VY, FY, gt=None, sym=None):
    """Geodesic error of a map X -> Y (paper §6): e_x = d_Y(map[x], gt[x]) / sqrt(area(Y)), exact
    geodesics, gt = identity when None; with sym (a symmetry map of X) the smaller of the errors to
    gt[x] and gt[sym[x]]. Returns (errors (nX,), mean)."""
    if not _clib.has("ss_map_geodesic_error"):
        raise NotImplementedError("this libspecseg has no ss_map_geodesic_error")
    my, VY, FY = _clib.as_mesh(VY, FY)
    mp = np.ascontiguousarray(map, dtype=np.int32).ravel()
    n = mp.size
    mp = _ints(mp, n, "map", VY.shape[0])
    if gt is None and n > VY.shape[0]:
        raise ValueError("identity ground truth needs a map with at most %d entries" % VY.shape[0])
    g = None if gt is None else _ints(gt, n, "gt", VY.shape[0])
    s = None if sym is None else _ints(sym, n, "sym", n)
    errs, mean, e = np.zeros(n), C.c_double(0), _err()
    check(lib.ss_map_geodesic_error(C.byref(my), n, _clib.ptr(mp, C.c_int), _clib.ptr(g, C.c_int),
                                    _clib.ptr(s, C.c_int), _clib.ptr(errs, C.c_double), C.byref(mean),
                                    C.byref(e)), e)
    return errs, mean.value


def align_labels(labels, ref):
    """Renumber segment ids of `labels` to agree with `ref` (same vertices) where they overlap most,
    as `specseg render --match-colors` does. Returns a new array."""
    lab = np.array(labels, dtype=np.int32).ravel()
    r = np.ascontiguousarray(ref, dtype=np.int32).ravel()
    if r.size != lab.size:
        raise ValueError("labels and ref must have the same length")
    e = _err()
    check(lib.ss_labels_align(_clib.ptr(lab, C.c_int), _clib.ptr(r, C.c_int), lab.size, C.byref(e)), e)
    return lab


def label_colors(labels):
    """(n, 3) uint8 colours of segment labels, as `specseg render --labels` draws them."""
    labels = np.asarray(labels, dtype=np.int64).ravel()
    table = {}
    out = np.zeros((labels.size, 3), np.uint8)
    for i, l in enumerate(labels):
        if l not in table:
            c = (C.c_ubyte * 3)()
            lib.ss_label_color(int(l), c)
            table[l] = tuple(c)
        out[i] = table[l]
    return out


_VIEWS = {"front": (0, 0), "back": (180, 0), "left": (90, 0), "right": (-90, 0), "top": (0, 90), "bottom": (0, -90)}


def render(V, F, labels=None, vertex_rgb=None, face_rgb=None, scalar=None, isolines=0, markers=None,
           size=(800, 800), view="front", supersample=2, background=(255, 255, 255)):
    """Software-rendered picture as an (H, W, 3) uint8 array.

    labels: segment per vertex (faces whose corners disagree drawn neutral, as `specseg render`);
    vertex_rgb / face_rgb: (n, 3) / (m, 3) uint8 colours; scalar: per-vertex field drawn with isolines
    (isolines levels; colour it yourself through vertex_rgb); markers: (k, 3) sphere centres;
    view: a name (front, back, left, right, top, bottom) or (azimuth, elevation) in degrees."""
    m, V, F = _clib.as_mesh(V, F)
    n, nf = V.shape[0], F.shape[0]
    if labels is not None:
        lab = np.asarray(labels).ravel()
        if lab.size != n:
            raise ValueError("labels must have one entry per vertex")
        lab = np.ascontiguousarray(lab, dtype=np.int32)
        face_rgb = np.zeros((nf, 3), np.uint8)
        e = _err()
        check(lib.ss_segmentation_face_colors(C.byref(m), _clib.ptr(lab, C.c_int), None,
                                              _clib.ptr(face_rgb, C.c_ubyte), C.byref(e)), e)
    fr = None if face_rgb is None else np.ascontiguousarray(face_rgb, dtype=np.uint8)
    vr = None if vertex_rgb is None else np.ascontiguousarray(vertex_rgb, dtype=np.uint8)
    if fr is not None and fr.shape != (nf, 3):
        raise ValueError("face_rgb must be (m, 3)")
    if vr is not None and vr.shape != (n, 3):
        raise ValueError("vertex_rgb must be (n, 3)")
    sc = _clib.ss_render_scene()
    lib.ss_render_scene_init(C.byref(sc), C.byref(m))
    sc.vertex_rgb, sc.face_rgb = _clib.ptr(vr, C.c_ubyte), _clib.ptr(fr, C.c_ubyte)
    sv = None
    if scalar is not None:
        sv = np.ascontiguousarray(scalar, dtype=np.float64).ravel()
        if sv.size != n:
            raise ValueError("scalar must have one entry per vertex")
        sc.scalar, sc.isolines = _clib.ptr(sv, C.c_double), int(isolines)
    mk = None
    if markers is not None:
        mk = np.ascontiguousarray(markers, dtype=np.float64).reshape(-1, 3)
        sc.nmarkers, sc.markers = mk.shape[0], _clib.ptr(mk, C.c_double)
    o = _clib.ss_render_options()
    lib.ss_render_default_options(C.byref(o))
    o.width, o.height = int(size[0]), int(size[1])
    if isinstance(view, str) and view not in _VIEWS:
        raise ValueError("view must be one of %s or (azimuth, elevation)" % ", ".join(_VIEWS))
    o.azimuth, o.elevation = _VIEWS[view] if isinstance(view, str) else (float(view[0]), float(view[1]))
    o.supersample = int(supersample)
    for c in range(3):
        o.background[c] = int(background[c])
    img, e = np.zeros((o.height, o.width, 3), np.uint8), _err()
    check(lib.ss_render(C.byref(sc), C.byref(o), _clib.ptr(img, C.c_ubyte), C.byref(e)), e)
    return img


def write_png(path, img):
    """Write an (H, W, 3) uint8 image as PNG."""
    img = np.ascontiguousarray(img, dtype=np.uint8)
    if img.ndim != 3 or img.shape[2] != 3:
        raise ValueError("img must be (H, W, 3) uint8")
    e = _err()
    check(lib.ss_write_png(str(path).encode(), _clib.ptr(img, C.c_ubyte), img.shape[1], img.shape[0], C.byref(e)), e)
