"""specseg — coherent spectral segmentation and functional-map matching of triangle meshes.

A thin ctypes binding over the C libraries (libspecseg.so, and libspecseg_render.so for pictures):
NumPy arrays in and out, errors raised as SpecsegError carrying the library's message. Meshes are
(V, F) pairs: V float64 (n, 3) vertex coordinates, F int32 (m, 3) 0-based vertex indices of the
triangles; other array types are converted, and integers that do not fit the library's int32 are
refused with ValueError rather than wrapped.

Where the C library is found: $SPECSEG_LIB (the library or its folder), beside the package, the
build folders of a source checkout, the install prefixes (sys.prefix/lib...), then the loader's own
search path; see specseg._clib for the details. `library_path` says which one was loaded,
`library_version()` its version.

    import specseg
    V, F = specseg.read_mesh("tr_reg_000.off")
    evals, evecs = specseg.eigs(V, F, k=10)
    seg = specseg.segment(V, F)                # seg.labels, seg.centers, seg.phi, ...
    d = specseg.geodesic(V, F, [412])          # exact geodesic distances
    img = specseg.render(V, F, labels=seg.labels)   # (H, W, 3) uint8
"""
import ctypes as C
import math
import os
from collections import namedtuple

import numpy as np

from . import _clib
from ._clib import LibraryVersionWarning, SpecsegError, lib
from ._clib import check as _check
from ._validate import as_float as _as_float, as_float64_array as _as_float64_array, as_int32 as _as_int32
from ._validate import as_int32_array as _as_int32_array, as_uint8_array as _as_uint8_array
from ._version import __version__

__all__ = ["SpecsegError", "LibraryVersionWarning", "read_mesh", "write_mesh", "laplacian", "eigs", "smooth",
           "remesh", "segment", "Segmentation", "geodesic", "wks", "hks", "match", "Match", "refine", "polish", "prepare", "Shape", "k_needed", "pair", "Pairing", "error", "render", "write_png",
           "label_colors", "align_labels", "library_version", "library_path", "render_library_path"]

#: Path of the loaded core library (libspecseg.so...).
library_path = _clib.lib_path
#: Path of the loaded render library, or None when it could not be loaded (then render, write_png,
#: label_colors and align_labels raise ImportError).
render_library_path = _clib.render_lib_path


def library_version():
    """The version of the loaded C library.

    Returns
    -------
    str or None
        ``ss_version()`` of the library at `library_path`, "MAJOR.MINOR.PATCH" (equal to
        ``__version__`` for a package and library built from the same source); None for a library
        older than 0.2, which has no ``ss_version``.
    """
    return _clib.library_version()


def _err():
    return _clib.ss_error()


def read_mesh(path):
    """Read a triangle mesh: OFF, OBJ, PLY, STL, glTF 2.0 or another format assimp reads.

    The format is chosen by the extension (case-insensitive), else by the content. Polygons are
    fan-triangulated; PLY and STL may be ASCII or binary. glTF 2.0 (.gltf with embedded or
    external buffers, .glb) is read by our own reader: all mesh instances of the scene merged with
    their node transforms applied. FBX, COLLADA, 3DS, ... are read through the Open Asset Import
    Library when the C library was built with libassimp-dev (coordinates are float32 values). An
    STL's and a scene's vertices with exactly equal coordinates are welded (in order of first
    occurrence), so an STL's per-facet vertex soup becomes one connected mesh.

    Parameters
    ----------
    path : str or os.PathLike
        The file to read.

    Returns
    -------
    V : numpy.ndarray of float64, shape (n, 3)
        Vertex coordinates (NaN / inf literals are read as such).
    F : numpy.ndarray of int32, shape (m, 3)
        Triangles as 0-based vertex indices.

    Raises
    ------
    SpecsegError
        The file cannot be read ("i/o error") or is malformed ("parse error": the message gives
        the file and line or byte offset, or the glTF element); an FBX / COLLADA / ... file with a
        library built without assimp ("unsupported", the message names libassimp-dev); a glTF that
        needs an unsupported extension or is glTF 1.0 ("unsupported").
    """
    m, e = _clib.ss_mesh(), _err()
    _check(lib.ss_read_mesh(os.fsencode(path), C.byref(m), C.byref(e)), e)
    return _clib.take_mesh(m)


def write_mesh(path, V, F, rgb=None):
    """Write a triangle mesh as .off (text) or .ply (binary little-endian), chosen by the extension.

    Coordinates are written losslessly: reading the file back gives the same arrays.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write; its extension (.off or .ply) selects the format.
    V : array_like of float, shape (n, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles as 0-based vertex indices, each in 0..n-1.
    rgb : array_like of int, shape (n, 3), optional
        Per-vertex colours, 0..255 (OFF becomes COFF, PLY gets red / green / blue properties).

    Returns
    -------
    None

    Raises
    ------
    ValueError
        Wrong shapes, a face index outside 0..n-1 or a colour outside 0..255.
    SpecsegError
        The file cannot be written, or its extension is neither .off nor .ply.
    """
    m, V, F = _clib.as_mesh(V, F)
    if rgb is not None:
        rgb = _as_uint8_array(rgb, "rgb")
        if rgb.shape != (V.shape[0], 3):
            raise ValueError("rgb must be an (n, 3) array of colours, n = %d (got shape %s)" % (V.shape[0], rgb.shape))
    e = _err()
    _check(lib.ss_write_mesh(os.fsencode(path), C.byref(m), _clib.ptr(rgb, C.c_ubyte), C.byref(e)), e)


def laplacian(V, F, mass="barycentric"):
    """Cotangent stiffness matrix and lumped masses: the discrete Laplace-Beltrami operator.

    W_ij = -(cot a_ij + cot b_ij) / 2 for each edge, W_ii = -sum_j W_ij, so that W phi = lambda M phi
    approximates the Laplace-Beltrami eigenproblem (lambda >= 0).

    Parameters
    ----------
    V : array_like of float, shape (n, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles as 0-based vertex indices.
    mass : {"barycentric", "voronoi"}, optional
        The lumped mass: a third of each incident triangle's area (default) or the mixed Voronoi
        areas of Meyer et al. 2003. Both sum to the surface area.

    Returns
    -------
    W : scipy.sparse.csc_matrix of float64, shape (n, n), or tuple
        Symmetric positive semi-definite, rows summing to zero. Without SciPy the CSC triple
        (indptr int32 (n+1,), indices int32 (nnz,), data float64 (nnz,)).
    M : numpy.ndarray of float64, shape (n,)
        The lumped masses.

    Raises
    ------
    ValueError
        An unknown `mass`, wrong shapes or a face index outside 0..n-1.
    SpecsegError
        The library refused the mesh.
    """
    kinds = {"barycentric": 0, "voronoi": 1}
    if mass not in kinds:
        raise ValueError("mass must be 'barycentric' or 'voronoi' (got %r)" % (mass,))
    m, V, F = _clib.as_mesh(V, F)
    n = V.shape[0]
    W, e = _clib.ss_sparse(), _err()
    _check(lib.ss_cotan_stiffness(C.byref(m), C.byref(W), C.byref(e)), e)
    try:
        nnz = W.colptr[W.ncols]
        indptr = _clib.copy_array(W.colptr, W.ncols + 1, np.int32)
        indices = _clib.copy_array(W.rowind, nnz, np.int32)
        data = _clib.copy_array(W.val, nnz, np.float64)
    finally:
        lib.ss_sparse_free(C.byref(W))
    M = np.zeros(n)
    _check(lib.ss_mass_lumped(C.byref(m), kinds[mass], _clib.ptr(M, C.c_double), C.byref(e)), e)
    try:
        import scipy.sparse as sp
        return sp.csc_matrix((data, indices, indptr), shape=(n, n)), M
    except ImportError:
        return (indptr, indices, data), M


def eigs(V, F, k):
    """The k smallest Laplace-Beltrami eigenpairs: W phi = lambda M phi with the cotangent stiffness W
    and barycentric masses M (ARPACK shift-invert on a CHOLMOD factorisation; deterministic).

    Parameters
    ----------
    V : array_like of float, shape (n, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles as 0-based vertex indices.
    k : int
        Number of eigenpairs, 1 <= k < n.

    Returns
    -------
    evals : numpy.ndarray of float64, shape (k,)
        Eigenvalues, ascending (exact zeros for the constant function of each component).
    evecs : numpy.ndarray of float64, shape (n, k)
        M-orthonormal eigenvectors, column j for evals[j].

    Raises
    ------
    ValueError
        k outside 1..n-1, wrong shapes or a face index outside 0..n-1.
    SpecsegError
        The mesh cannot be processed ("invalid input", e.g. zero masses) or the eigensolver failed
        ("numerical failure").
    """
    m, V, F = _clib.as_mesh(V, F)
    n = V.shape[0]
    if n < 2:
        raise ValueError("eigs needs a mesh with at least 2 vertices (got %d)" % n)
    k = _as_int32(k, "k", 1, n - 1)
    evals, evecs = np.zeros(k), np.zeros((k, n))  # column-major n x k == row-major k x n
    e = _err()
    _check(_clib.compute(lib.ss_mesh_eigs, C.byref(m), k, _clib.ptr(evals, C.c_double), _clib.ptr(evecs, C.c_double),
                         C.byref(e)), e)
    return evals, np.ascontiguousarray(evecs.T)


def _descriptors(fn, V, F, k, n, extra):
    m, V, F = _clib.as_mesh(V, F)
    nv = V.shape[0]
    if nv < 4:
        raise ValueError("descriptors need a mesh with at least 4 vertices (got %d)" % nv)
    k = _as_int32(k, "k", 3, nv - 1)
    n = _as_int32(n, "n", 1, 10000)
    evals, evecs = np.zeros(k), np.zeros((k, nv))  # column-major nv x k
    M, D = np.zeros(nv), np.zeros((n, nv))
    e = _err()
    with _clib.one_blas_thread():
        _check(lib.ss_mesh_eigs(C.byref(m), k, _clib.ptr(evals, C.c_double), _clib.ptr(evecs, C.c_double), C.byref(e)), e)
        _check(lib.ss_mass_lumped(C.byref(m), 0, _clib.ptr(M, C.c_double), C.byref(e)), e)
        _check(fn(nv, k, _clib.ptr(evals, C.c_double), _clib.ptr(evecs, C.c_double), _clib.ptr(M, C.c_double), n,
                  *extra, _clib.ptr(D, C.c_double), C.byref(e)), e)
    return np.ascontiguousarray(D.T)


def wks(V, F, k=100, n=100):
    """Wave kernel signature (Aubry et al. 2011) per vertex, as ``specseg descriptors --wks``.

    From the k smallest Laplace-Beltrami eigenpairs (barycentric masses): n log-spaced energies with
    sigma = 7 energy spacings, the zero eigenvalue filtered out, each column normalised to unit L2(M)
    norm — the WKS ``specseg match`` uses (its defaults: descriptors from 100 eigenpairs, n = 100). The result can be saved with
    numpy.save and given to ``specseg match --descriptors``, or passed to `match` as ``descriptors``.

    Parameters
    ----------
    V : array_like of float, shape (nv, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles as 0-based vertex indices.
    k : int, optional
        Eigenpairs, 3 <= k < nv (default 100, the eigenpairs `match` computes its WKS from).
    n : int, optional
        Energies, 1..10000 (default 100).

    Returns
    -------
    numpy.ndarray of float64, shape (nv, n)

    Raises
    ------
    ValueError
        k or n out of range, wrong shapes or a face index outside 0..nv-1.
    SpecsegError
        The eigensolver or the filters failed (e.g. fewer than two distinct non-zero eigenvalues).
    """
    return _descriptors(lib.ss_wks, V, F, k, n, (C.c_double(7.0),))


def hks(V, F, k=100, n=100):
    """Heat kernel signature (Sun et al. 2009) per vertex, as ``specseg descriptors --hks``.

    From the k smallest Laplace-Beltrami eigenpairs: n times log-spaced from 4 ln 10 / lambda_max to
    4 ln 10 / lambda_1, HKS(x, t) = sum_i exp(-lambda_i t) phi_i(x)^2 without the constant function,
    each column normalised to unit L2(M) norm (as `wks`).

    Parameters
    ----------
    V : array_like of float, shape (nv, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles as 0-based vertex indices.
    k : int, optional
        Eigenpairs, 3 <= k < nv (default 100, as `wks`).
    n : int, optional
        Times, 1..10000 (default 100).

    Returns
    -------
    numpy.ndarray of float64, shape (nv, n)

    Raises
    ------
    ValueError
        k or n out of range, wrong shapes or a face index outside 0..nv-1.
    SpecsegError
        The eigensolver failed.
    """
    return _descriptors(lib.ss_hks, V, F, k, n, ())


def smooth(V, F, steps=None, dt=None):
    """Conformalized mean curvature flow (paper §4.1): fingers, toes and ears collapse, the limbs stay.

    The result keeps the input's connectivity and vertex order and is returned at the input's scale
    and position (same total area, same area-weighted centroid).

    Parameters
    ----------
    V : array_like of float, shape (n, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles as 0-based vertex indices.
    steps : int, optional
        Number of implicit flow steps, >= 0 (library default 12).
    dt : float, optional
        Time step, measured at unit area; positive and finite (library default 2.2e-5).

    Returns
    -------
    numpy.ndarray of float64, shape (n, 3)
        The smoothed vertex coordinates (the faces are F).

    Raises
    ------
    ValueError
        steps outside the int32 range, dt not a positive finite number, wrong shapes or a face
        index outside 0..n-1.
    SpecsegError
        An empty or zero-area mesh, a negative step count, non-finite coordinates ("invalid
        input") or a failed factorisation ("numerical failure").
    """
    m, V, F = _clib.as_mesh(V, F)
    o = _clib.ss_cmcf_options()
    lib.ss_cmcf_default_options(C.byref(o))
    if steps is not None:
        o.steps = _as_int32(steps, "steps")
    if dt is not None:
        o.dt = _as_float(dt, "dt", positive=True)
    out, e = _clib.ss_mesh(), _err()
    _check(_clib.compute(lib.ss_cmcf_smooth, C.byref(m), C.byref(o), C.byref(out), C.byref(e)), e)
    V2, _ = _clib.take_mesh(out)
    return V2


def remesh(V, F, target_faces=15000):
    """Isotropic remeshing (Botsch & Kobbelt 2004) to about `target_faces` triangles.

    The output has the input's components and genus and all its vertices lie on the input surface.

    Parameters
    ----------
    V : array_like of float, shape (n, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles of a closed (no boundary edges), edge-manifold mesh, 0-based vertex indices.
    target_faces : int, optional
        The wanted triangle count, >= 4 (default 15000); the result is within about 2 of it.

    Returns
    -------
    V2 : numpy.ndarray of float64, shape (n2, 3)
        Vertex coordinates of the new mesh.
    F2 : numpy.ndarray of int32, shape (m2, 3)
        Its triangles.

    Raises
    ------
    ValueError
        target_faces outside the int32 range, wrong shapes or a face index outside 0..n-1.
    SpecsegError
        An open mesh ("unsupported"), a target below 4 or non-finite coordinates ("invalid input").
    """
    m, V, F = _clib.as_mesh(V, F)
    o = _clib.ss_remesh_options()
    lib.ss_remesh_default_options(C.byref(o))
    o.target_faces = _as_int32(target_faces, "target_faces")
    out, e = _clib.ss_mesh(), _err()
    _check(_clib.compute(lib.ss_remesh, C.byref(m), C.byref(o), C.byref(out), C.byref(e)), e)
    return _clib.take_mesh(out)


Segmentation = namedtuple("Segmentation", "labels centers m phi lambda2 work_V work_F psi crit work_labels "
                                          "ncrit_raw empty_segments")
Segmentation.__doc__ = """The result of `segment`.

Attributes
----------
labels : numpy.ndarray of int32, shape (n,)
    Segment 0..m-1 of each input vertex.
centers : numpy.ndarray of int32, shape (m,)
    The input vertex at the centre of each segment.
m : int
    Number of segments (critical points of the Fiedler vector after the clean-up).
phi : numpy.ndarray of float64, shape (nw,)
    The Fiedler vector on the work mesh (M-normalised, largest-magnitude entry positive).
lambda2 : float
    Its eigenvalue.
work_V : numpy.ndarray of float64, shape (nw, 3)
    The work mesh: the input smoothed and remeshed (a copy of the input with no_streamline).
work_F : numpy.ndarray of int32, shape (mw, 3)
    Its triangles.
psi : numpy.ndarray of int32, shape (n,)
    Input vertex -> closest work vertex to its smoothed twin; -1 for a vertex no face uses.
crit : numpy.ndarray of int32, shape (m,)
    The work vertex of each segment's critical point.
work_labels : numpy.ndarray of int32, shape (nw,)
    Segment of each work vertex (its intrinsic Voronoi cell).
ncrit_raw : int
    Critical points before the clean-up.
empty_segments : int
    Segments that no input vertex fell in.
"""


def segment(V, F, target_faces=None, no_streamline=False, cleanup_rings=None, sanitize=None):
    """Coherent segmentation (paper §4): smoothing, remeshing, the Fiedler vector's critical points
    and their intrinsic Voronoi diagram, mapped back to the input vertices.

    Parameters
    ----------
    V : array_like of float, shape (n, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles as 0-based vertex indices (boundary loops are closed internally).
    target_faces : int, optional
        Triangle count of the remeshed work mesh, >= 4 (library default 15000).
    no_streamline : bool, optional
        Work on the input itself: no smoothing and remeshing (default False).
    cleanup_rings : int, optional
        Critical-point clean-up radius in rings, >= 0; 0 turns it off (library default 5).
    sanitize : bool, optional
        Repair pinched vertices and degenerate faces first (library default True).

    Returns
    -------
    Segmentation
        labels, centers, m, phi, lambda2, work_V, work_F, psi, crit, work_labels, ncrit_raw,
        empty_segments (see `Segmentation`).

    Raises
    ------
    ValueError
        An integer option outside the int32 range, wrong shapes or a face index outside 0..n-1.
    SpecsegError
        The library refused the options (e.g. target_faces < 4, cleanup_rings < 0) or the mesh, or a
        stage failed numerically.
    """
    m, V, F = _clib.as_mesh(V, F)
    o = _clib.ss_segment_options()
    lib.ss_segment_default_options(C.byref(o))
    if target_faces is not None:
        o.target_faces = _as_int32(target_faces, "target_faces")
    o.no_streamline = 1 if no_streamline else 0
    if cleanup_rings is not None:
        o.cleanup_rings = _as_int32(cleanup_rings, "cleanup_rings")
    if sanitize is not None:
        o.sanitize = 1 if sanitize else 0
    s, e = _clib.ss_segmentation(), _err()
    st = _clib.compute(lib.ss_segment, C.byref(m), C.byref(o), C.byref(s), C.byref(e))
    try:
        _check(st, e)
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
    """Geodesic distance from every vertex to the nearest of the source vertices.

    Parameters
    ----------
    V : array_like of float, shape (n, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles as 0-based vertex indices.
    sources : int or array_like of int, shape (s,)
        Source vertices, each in 0..n-1 (at least one).
    method : {"exact", "graph", "edge"}, optional
        Exact polyhedral geodesics (VTP, the default), Dijkstra on the NPP22 graph, or Dijkstra on
        the mesh edges.
    max_dist : float, optional
        Stop the propagation past this distance; farther vertices get inf. None (default) or inf: no
        limit. As the CLI's --max-dist it must be positive: 0, a negative value or NaN raise
        ValueError.

    Returns
    -------
    numpy.ndarray of float64, shape (n,)
        The distances; 0 at the sources, inf where unreached.

    Raises
    ------
    ValueError
        An unknown method, no sources, a source outside 0..n-1 (in particular one that does not
        fit an int32), max_dist NaN, wrong shapes or a face index outside 0..n-1.
    SpecsegError
        The library refused the mesh (e.g. non-finite coordinates).
    """
    if method not in _METHODS:
        raise ValueError("method must be one of %s (got %r)" % (", ".join(_METHODS), method))
    m, V, F = _clib.as_mesh(V, F)
    src = _as_int32_array(np.atleast_1d(sources), "sources", 0, V.shape[0] - 1).ravel()
    if src.size == 0:
        raise ValueError("sources is empty: give at least one vertex index")
    d, e = np.zeros(V.shape[0]), _err()
    md = math.inf if max_dist is None else _as_float(max_dist, "max_dist", allow_inf=True)
    if not md > 0:  # as the CLI's --max-dist: a negative bound meant "no limit" in the library
        raise ValueError("max_dist must be positive (None or inf: no limit), not %r" % (max_dist,))
    _check(lib.ss_geodesic_distances(C.byref(m), _METHODS[method], _clib.ptr(src, C.c_int), src.size, md,
                                    _clib.ptr(d, C.c_double), C.byref(e)), e)
    return d


def _indices(a, n, what, hi):
    """A 1-D int32 array of n entries, each in 0..hi-1."""
    a = _as_int32_array(np.atleast_1d(a), what, 0, hi - 1)
    if a.ndim != 1 or a.shape[0] != n:
        raise ValueError("%s must be a vector of %d entries (got shape %s)" % (what, n, a.shape))
    return a


Match = namedtuple("Match",
                   "map C pairs_x pairs_y centers_x centers_y notes confident hypothesis margin hypotheses coverage",
                   defaults=(None, None, (), None))
Match.__doc__ = """The result of `match`.

Attributes
----------
map : numpy.ndarray of int32, shape (nX,)
    The point map: vertex of Y for each vertex of X.
C : numpy.ndarray of float64, shape (kc, kc)
    The functional map from functions on Y to functions on X (kc = k, or the ZoomOut size), in the
    eigenbases of both shapes scaled to unit area (so it does not depend on either shape's size).
pairs_x, pairs_y : numpy.ndarray of int32, shape (p,)
    The paired segments: segment pairs_x[i] of X with segment pairs_y[i] of Y (empty with
    probes="std" and landmarks: its map uses no segments, so none are paired).
centers_x, centers_y : numpy.ndarray of int32, shape (p,)
    The input vertices at the centres of the paired segments.
notes : str
    What the caller should know (e.g. a landmark-free pairing that is not confident); "" if nothing.
confident : bool or None
    Landmark-free: whether the automatic pairing was confident; None with landmarks.
hypothesis : int or None
    Where several maps were made (landmark-free, or hypotheses beside landmarks): the index of the
    one kept in `hypotheses`; None otherwise.
margin : float or None
    Its hypothesis energy's margin over the next differing candidate (``hypothesis_margin`` of
    ``specseg match --json``); None where one map was made.
hypotheses : tuple of dict
    Each candidate map's numbers, as ``specseg match --json``: energy (the sum the choice minimises),
    distortion, reversed, orientation, orientation_min, pair_energy, map_energy, differ, scale (NaN
    where the CLI writes null), "from" ("X", or "Y" for Y's pairing hypotheses read back), and
    flip_of / flip_by for a flipped candidate. Empty when one map was made.
coverage : float or None
    Where hypotheses were formed (landmark-free, or beside landmarks): the map's distinct images over
    the smaller shape's vertex count (``coverage`` of ``specseg match --json``); below min_coverage
    the map is not confident. None otherwise.
"""

_PROBES = {"std": 0, "asa": 1, "diff": 2}


def match(VX, FX, VY=None, FY=None, landmarks=None, landmarks_y=None, probes="diff", k=None, zoomout=None,
          segment_profile=None, descriptors=None, wks=True, orient=None, zoomout_step=None, zoomout_samples=None,
          descr_k=None, hypotheses=None, one_way=False, flip_by=None, final_zoomout=None, polish=True, recheck=True,
          scale_fit=False, skip_tol=None, min_coverage=None):
    """Point map X -> Y by the paper's pipeline (§6): segmentation of both shapes, pairing of the
    segments through the landmarks, a functional map with STD / ASA / DIFF probes, optional ZoomOut.

    ``match(X, Y, landmarks, ...)`` with two `Shape` objects (`prepare`, `Shape.load`) matches the
    prepared shapes without preparing them again: the same result as from their meshes when each was
    prepared with exactly the eigenpairs this match needs (`Shape.k`, `k_needed`; the default prepare
    fits every default match), an error naming the shape when one has fewer.

    Parameters
    ----------
    VX : array_like of float, shape (nX, 3)
        Vertex coordinates of X.
    FX : array_like of int, shape (mX, 3)
        Triangles of X, 0-based vertex indices.
    VY : array_like of float, shape (nY, 3)
        Vertex coordinates of Y.
    FY : array_like of int, shape (mY, 3)
        Triangles of Y.
    landmarks : array_like of int, shape (l,), optional
        Landmark vertices on X, each in 0..nX-1 (and on Y too unless landmarks_y is given). None:
        landmark-free, the segments paired automatically (see `pair`); a pairing that is not
        confident is reported in the result's notes.
    landmarks_y : array_like of int, shape (l,), optional
        The corresponding vertices on Y, each in 0..nY-1.
    probes : {"diff", "asa", "std"}, optional
        The probe functions: WKS + landmark maps (std), plus the paired segments as they are (asa)
        or filtered by the wave kernel (diff, the default).
    k : int, optional
        Basis size on both shapes, >= 3 (library default 50).
    zoomout : int, optional
        Refine the map with ZoomOut up to this basis size (>= k); 0 or None: no ZoomOut.
    segment_profile : {"indicator", "tent", "soft"}, optional
        The paired segments' probe functions, as ``specseg match --segment-profile`` (library default
        "tent").
    orient : float, optional
        Weight of the orientation-preserving term (Ren et al. 2018; ``specseg match --orient``), 0..1e6
        (library default 0.001; 0: the paper's Eq. (1) without it).
    descriptors : (array_like, array_like), optional
        Your own per-vertex descriptors (DX, DY) of shapes (nX, d) and (nY, d), column j of DX
        corresponding to column j of DY (e.g. `wks` / `hks`, or any features), as
        ``specseg match --descriptors``: extra probes used as they are, each normalised in L2(M).
    wks : bool, optional
        False: no WKS among the probes (the descriptors replace it; needs `descriptors`), as
        ``--no-wks``. Default True.
    zoomout_step : int, optional
        ZoomOut's size increment, 1..10000 (``--zoomout-step``; library default 5).
    zoomout_samples : int, optional
        ZoomOut's iterations on this many samples of X, 0..10**9 (``--zoomout-samples``; library
        default 1000; 0: on every vertex).
    descr_k : int, optional
        Eigenpairs the descriptors are computed from, >= 3 (``--descr-k``; library default 100; raised
        to k when below it, as the CLI does).

    The hypotheses (landmark-free; beside landmarks where the library maps them too), as the CLI's
    flags of the same names:

    hypotheses : int, optional
        Pairing hypotheses mapped from each direction, 1..16 (``--hypotheses``; default 4).
    one_way : bool, optional
        True: X's own pairing hypotheses only, not also Y's read the other way (``--one-way``).
    flip_by : {"x", "y", "both"}, optional
        Whose left-right symmetry turns a mirrored hypothesis round (``--flip-by``; default "both").
    final_zoomout : int, optional
        The map kept refined further by ZoomOut up to this size, 0..10000 (``--final-zoomout``;
        default 150; 0: not).
    polish : bool, optional
        False: the map kept is not fitted to the surfaces (``--no-polish``). Default True.
    recheck : bool, optional
        False: a choice in doubt is not rechecked on polished maps (``--no-recheck``). Default True.
    scale_fit : bool, optional
        True: the hypotheses' distortion compares distances up to one scale per map, for two bodies
        of different build (``--scale-fit``; docs/tuning.md). Default False.
    skip_tol : float, optional
        Without landmarks, a candidate whose landmarks an earlier candidate's map already sends
        within this many sqrt(area) of their partners is not mapped (``--skip-tol``; 0..1e6, default
        0: every one is). 0.05 takes about 0.8x the time; the candidate's own energy is lost, so the
        choice and the confidence may change (docs/tuning.md).
    min_coverage : float, optional
        The map is not confident when its distinct images make up less than this share of the
        smaller shape's vertices (``--min-coverage``; 0..1, default 0.65; 0: not used).

    Returns
    -------
    Match
        map, C, pairs_x, pairs_y, centers_x, centers_y, notes, confident, and the hypotheses behind
        the choice (see `Match`).

    Raises
    ------
    ValueError
        Unknown probes / segment_profile / flip_by, landmarks out of range or of different lengths,
        an integer option outside its range, wrong shapes or face indices out of range.
    SpecsegError
        The library refused the options (e.g. k < 3, zoomout < k) or a mesh (e.g. one its sanitizer
        would change), or a stage failed.
    NotImplementedError
        The loaded library has no ss_match.
    """
    if not _clib.has("ss_match"):
        raise NotImplementedError("this libspecseg (%s) has no ss_match" % library_path)
    if probes not in _PROBES:
        raise ValueError("probes must be std, asa or diff (got %r)" % (probes,))
    profiles = {"indicator": 0, "tent": 1, "soft": 2}
    if segment_profile is not None and segment_profile not in profiles:
        raise ValueError("segment_profile must be indicator, tent or soft (got %r)" % (segment_profile,))
    shapes = isinstance(VX, Shape) or isinstance(FX, Shape)
    if shapes:
        if not (isinstance(VX, Shape) and isinstance(FX, Shape)):
            raise ValueError("match takes two Shape objects or two meshes (VX, FX, VY, FY)")
        X, Y = VX, FX
        X._check(), Y._check()
        # match(X, Y, landmarks, landmarks_y): the positions of VY and FY
        if VY is not None:
            if landmarks is not None:
                raise ValueError("landmarks given twice")
            landmarks, VY = VY, None
        if FY is not None:
            if landmarks_y is not None:
                raise ValueError("landmarks_y given twice")
            landmarks_y, FY = FY, None
        nX, nY = X.n, Y.n
    else:
        if VY is None or FY is None:
            raise ValueError("match needs VX, FX, VY, FY (or two Shape objects)")
        mx, VX, FX = _clib.as_mesh(VX, FX)
        my, VY, FY = _clib.as_mesh(VY, FY)
        nX, nY = VX.shape[0], VY.shape[0]
    if landmarks is None:
        if landmarks_y is not None:
            raise ValueError("landmarks_y without landmarks")
        lx = ly = np.zeros(0, dtype=np.int32)
    else:
        lx = np.atleast_1d(landmarks)
        lx = _indices(lx, lx.size, "landmarks", nX)
        ly = _indices(lx if landmarks_y is None else landmarks_y, lx.size, "landmarks_y", nY)
        if lx.size == 0:
            raise ValueError("landmarks is empty: give at least one landmark vertex (or None: landmark-free)")
    o = _clib.ss_match_options()
    lib.ss_match_default_options(C.byref(o))
    o.probes = _PROBES[probes]
    if k is not None:
        o.fmap.k = _as_int32(k, "k")
    if zoomout is not None:
        o.fmap.zoomout_kmax = _as_int32(zoomout, "zoomout")
    if segment_profile is not None:
        o.segment_profile = profiles[segment_profile]
    if orient is not None:
        w = float(orient)
        if not (0 <= w <= 1e6):
            raise ValueError(f"orient must be a weight in [0, 1e6], not {orient!r}")
        o.fmap.w_orient = w
    _hypothesis_options(o, zoomout_step, zoomout_samples, descr_k, hypotheses, one_way, flip_by, final_zoomout,
                        polish, recheck, scale_fit, skip_tol, min_coverage)
    if not wks and descriptors is None:
        raise ValueError("wks=False needs descriptors: they replace the WKS")
    o.fmap.no_wks = 0 if wks else 1
    if descriptors is not None:
        if len(descriptors) != 2:
            raise ValueError("descriptors must be a pair (DX, DY)")
        DX, DY = (_as_float64_array(d, name, finite=True)
                  for d, name in zip(descriptors, ("descriptors[0]", "descriptors[1]")))
        if DX.ndim == 1:
            DX = DX[:, None]
        if DY.ndim == 1:
            DY = DY[:, None]
        if DX.ndim != 2 or DX.shape[0] != nX:
            raise ValueError("descriptors[0] must be (nX, d) with nX = %d (got shape %s)" % (nX, DX.shape))
        if DY.ndim != 2 or DY.shape[0] != nY:
            raise ValueError("descriptors[1] must be (nY, d) with nY = %d (got shape %s)" % (nY, DY.shape))
        if DX.shape[1] != DY.shape[1]:
            raise ValueError("descriptors: %d columns on X, %d on Y (they must correspond)" % (DX.shape[1], DY.shape[1]))
        if DX.shape[1] == 0 or not (np.isfinite(DX).all() and np.isfinite(DY).all()):
            raise ValueError("descriptors must have at least one column and finite values")
        DX, DY = np.asfortranarray(DX), np.asfortranarray(DY)  # column-major nX x d
        o.ndescr = _as_int32(DX.shape[1], "descriptor columns")
        o.descrX, o.descrY = _clib.ptr(DX, C.c_double), _clib.ptr(DY, C.c_double)
    r, e = _clib.ss_match_result(), _err()
    if shapes:
        st = _clib.compute(lib.ss_match_prepared_shapes, C.byref(X._s), C.byref(Y._s), lx.size, _clib.ptr(lx, C.c_int),
                           _clib.ptr(ly, C.c_int), C.byref(o), C.byref(r), None, 0, C.byref(e))
    else:
        st = _clib.compute(lib.ss_match, C.byref(mx), C.byref(my), lx.size, _clib.ptr(lx, C.c_int),
                           _clib.ptr(ly, C.c_int), C.byref(o), C.byref(r), C.byref(e))
    try:
        _check(st, e)
        cp = _clib.copy_array
        Cm = cp(r.C, r.kc * r.kc, np.float64).reshape(r.kc, r.kc).T.copy() if r.kc else np.zeros((0, 0))
        return Match(map=cp(r.map, r.nX, np.int32), C=Cm, pairs_x=cp(r.pairs.sx, r.pairs.n, np.int32),
                     pairs_y=cp(r.pairs.sy, r.pairs.n, np.int32), centers_x=cp(r.centerX, r.pairs.n, np.int32),
                     centers_y=cp(r.centerY, r.pairs.n, np.int32), notes=r.notes.decode("utf-8", "replace"),
                     confident=None if not r.autopair.used else bool(r.autopair.confident),
                     hypothesis=int(r.autopair.hypothesis) if r.autopair.hypotheses > 1 else None,
                     margin=float(r.autopair.hyp_margin) if r.autopair.hypotheses > 1 else None,
                     hypotheses=_hypotheses_info(r.autopair),
                     coverage=float(r.autopair.coverage) if r.autopair.used or r.autopair.hypotheses > 1 else None)
    finally:
        lib.ss_match_result_free(C.byref(r))


def _hypothesis_options(o, zoomout_step, zoomout_samples, descr_k, hypotheses, one_way, flip_by, final_zoomout,
                        polish, recheck, scale_fit, skip_tol, min_coverage=None):
    """match()'s refinement and hypothesis keywords into the options o, with the CLI's ranges."""
    if zoomout_step is not None:
        o.fmap.zoomout_step = _as_int32(zoomout_step, "zoomout_step", 1, 10000)
    if zoomout_samples is not None:
        o.fmap.zoomout_samples = _as_int32(zoomout_samples, "zoomout_samples", 0, 10 ** 9)
    if descr_k is not None:
        o.fmap.descr_k = _as_int32(descr_k, "descr_k", 3, 10000)
    if o.fmap.descr_k < o.fmap.k:  # a larger k takes the descriptors along (as specseg match)
        o.fmap.descr_k = o.fmap.k
    if hypotheses is not None:
        o.autopair.hypotheses = _as_int32(hypotheses, "hypotheses", 1, _clib.MAX_HYPOTHESES)
    if final_zoomout is not None:
        o.autopair.hyp_final_kmax = _as_int32(final_zoomout, "final_zoomout", 0, 10000)
    sides = {"x": 0, "y": 1, "both": 2}
    if flip_by is not None:
        if not isinstance(flip_by, str) or flip_by not in sides:
            raise ValueError("flip_by must be x, y or both (got %r)" % (flip_by,))
        o.autopair.hyp_flip_side = sides[flip_by]
    if one_way:
        o.autopair.hyp_reverse = 0
    if not polish:
        o.autopair.hyp_final_polish = 0
    if not recheck:
        o.autopair.hyp_recheck_window = 0
    if scale_fit:
        o.autopair.hyp_fit_scale = 1
    if skip_tol is not None:
        t = _as_float(skip_tol, "skip_tol")
        if not 0 <= t <= 1e6:
            raise ValueError("skip_tol must be in [0, 1e6], not %r" % (skip_tol,))
        o.autopair.hyp_skip_tol = t
    if min_coverage is not None:
        t = _as_float(min_coverage, "min_coverage")
        if not 0 <= t <= 1:
            raise ValueError("min_coverage must be in [0, 1], not %r" % (min_coverage,))
        o.autopair.hyp_min_coverage = t


_HYP_KEYS = ("energy", "distortion", "reversed", "orientation", "orientation_min", "pair_energy", "map_energy",
             "differ", "scale")


def _hypotheses_info(a):
    """The hypotheses' numbers of an ss_autopair_info as a tuple of dicts (the keys of `specseg match
    --json`'s "hypotheses"; NaN where the CLI writes null); () when one map was made."""
    if a.hypotheses <= 1:
        return ()
    out = []
    for h in range(min(a.hypotheses, _clib.MAX_HYPOTHESES)):
        d = {key: float(getattr(a, "hyp_" + key)[h]) for key in _HYP_KEYS}
        d["from"] = "Y" if a.hyp_from_y[h] else "X"
        if a.hyp_flip_of[h] >= 0:
            d["flip_of"], d["flip_by"] = int(a.hyp_flip_of[h]), "Y" if a.hyp_flip_by_y[h] else "X"
        if a.hyp_skipped_by[h] >= 0:
            d["skipped_by"] = int(a.hyp_skipped_by[h])
        out.append(d)
    return tuple(out)


def _shape_pair(VX, FX, VY, FY, map, what):
    """(X, Y, map) when refine / polish got two Shape objects and the map (VX, FX, VY or map=), None
    when they got meshes; refuses a mix."""
    if not (isinstance(VX, Shape) or isinstance(FX, Shape)):
        if VY is None or FY is None:
            raise ValueError("%s needs VX, FX, VY, FY and the map (or two Shape objects and the map)" % what)
        return None
    if not (isinstance(VX, Shape) and isinstance(FX, Shape)):
        raise ValueError("%s takes two Shape objects or two meshes (VX, FX, VY, FY)" % what)
    if map is None and FY is None:
        map, VY = VY, None
    if VY is not None or FY is not None:
        raise ValueError("%s(X, Y, map) with Shape objects: no VY / FY" % what)
    return VX, FX, map


def _map_entries(map, nX, nY, what):
    """The map as int32 entries checked against X's and Y's vertex counts."""
    if map is None:
        raise ValueError("%s needs the map to %s" % (what, what))
    m = np.atleast_1d(np.asarray(map))
    if m.ndim != 1 or m.size != nX:
        raise ValueError("map must have one entry per vertex of X (%d), got shape %s" % (nX, m.shape))
    return _indices(m, nX, "map", nY)


def refine(VX, FX, VY=None, FY=None, map=None, k=None, zoomout=None, zoomout_step=None, zoomout_samples=None):
    """A given point map X -> Y (another method's, or a rough one) through the refinement `match`
    gives its own maps: the map's functional map on the first k eigenfunctions of both shapes (scaled
    to unit area), then ZoomOut up to `zoomout` on vertex samples of X and once on every vertex, as
    ``specseg refine``. ZoomOut mends local errors; a whole part mapped to the wrong place (a
    left-right swap) stays.

    ``refine(X, Y, map, ...)`` with two `Shape` objects uses their eigenpairs (each needs at least
    max(k, zoomout)); with meshes the eigenpairs are computed here.

    Parameters
    ----------
    VX, FX, VY, FY : array_like
        The meshes X (nX vertices) and Y (nY vertices), as `match` takes them; or two Shape objects
        as VX and FX, the map then third.
    map : array_like of int, shape (nX,)
        Entry i is the vertex of Y (0..nY-1) that vertex i of X goes to.
    k : int, optional
        The start's basis size, >= 1 (library default 50).
    zoomout : int, optional
        ZoomOut up to this size, >= k (library default 110); equal to k: no ZoomOut, the map through
        its own k x k functional map.
    zoomout_step : int, optional
        ZoomOut's size increment, >= 1 (library default 5).
    zoomout_samples : int, optional
        ZoomOut's iterations on this many samples of X, >= 0 (library default 1000; 0: every vertex).

    Returns
    -------
    (numpy.ndarray of int32, shape (nX,), numpy.ndarray of float64, shape (kz, kz))
        The refined map and its functional map (functions on Y to functions on X, kz = max(k,
        zoomout)).

    Raises
    ------
    ValueError
        A map of the wrong length or with entries off Y, sizes outside the int32 range, zoomout < k,
        a Shape matched through a coarse proxy, wrong mesh shapes.
    SpecsegError
        The library refused the shapes (too few eigenpairs, a mesh its sanitizer would change) or
        the sizes.
    """
    if not _clib.has("ss_match_refine"):
        raise NotImplementedError("this libspecseg (%s) has no ss_match_refine" % library_path)
    pair = _shape_pair(VX, FX, VY, FY, map, "refine")
    shapes = pair is not None
    if shapes:
        X, Y, map = pair
        X._check(), Y._check()
        for name, sh in (("X", X), ("Y", Y)):
            if sh._s.has_proxy:
                raise ValueError("%s is matched through a coarse proxy (above 100,000 vertices): refine its mesh" % name)
        nX, nY = X.n, Y.n
    else:
        mx, VX, FX = _clib.as_mesh(VX, FX)
        my, VY, FY = _clib.as_mesh(VY, FY)
        nX, nY = VX.shape[0], VY.shape[0]
    m = _map_entries(map, nX, nY, "refine")
    o = _clib.ss_match_options()
    lib.ss_match_default_options(C.byref(o))
    for val, name, field, lo in ((k, "k", "k", 1), (zoomout, "zoomout", "zoomout_kmax", 1),
                                 (zoomout_step, "zoomout_step", "zoomout_step", 1),
                                 (zoomout_samples, "zoomout_samples", "zoomout_samples", 0)):
        if val is not None:
            setattr(o.fmap, field, _as_int32(val, name, lo))
    if o.fmap.zoomout_kmax < o.fmap.k:
        raise ValueError("zoomout %d is below k %d" % (o.fmap.zoomout_kmax, o.fmap.k))
    kz = max(o.fmap.k, o.fmap.zoomout_kmax)
    out, Cm, e = np.zeros(nX, dtype=np.int32), np.zeros(kz * kz), _err()
    own = []
    try:
        if shapes:
            px, py = C.byref(X._s.prep), C.byref(Y._s.prep)
        else:
            for mesh in (mx, my):
                p = _clib.ss_shape_prep()
                st = _clib.compute(lib.ss_shape_prep_compute_spectral, C.byref(mesh), kz, C.byref(p), C.byref(e))
                if st == 0:
                    own.append(p)
                _check(st, e)
            px, py = C.byref(own[0]), C.byref(own[1])
        _check(_clib.compute(lib.ss_match_refine, px, py, _clib.ptr(m, C.c_int), C.byref(o), _clib.ptr(out, C.c_int),
                             _clib.ptr(Cm, C.c_double), C.byref(e)), e)
    finally:
        for p in own:
            lib.ss_shape_prep_free(C.byref(p))
    return out, Cm.reshape(kz, kz).T.copy()


def polish(VX, FX, VY=None, FY=None, map=None):
    """A point map X -> Y fitted to the surfaces, as ``specseg refine --polish-only`` and the last
    step of a landmark-free `match`: X, deformed as rigidly as possible, is pulled onto Y (the nearest
    vertex of Y facing the same way) and, less and less, towards the map's images; each vertex then
    goes to the nearest vertex of Y facing the same way, at most 0.1 sqrt(area) from its given image
    along Y's edges. It mends the error of about one edge length that ZoomOut leaves where the poses
    stretch the surface; a part mapped to the wrong place stays. Needs each mesh consistently oriented.

    ``polish(X, Y, map)`` with two `Shape` objects uses their meshes.

    Parameters
    ----------
    VX, FX, VY, FY : array_like
        The meshes X (nX vertices) and Y (nY vertices); or two Shape objects as VX and FX, the map
        then third.
    map : array_like of int, shape (nX,)
        Entry i is the vertex of Y (0..nY-1) that vertex i of X goes to.

    Returns
    -------
    numpy.ndarray of int32, shape (nX,)
        The polished map.

    Raises
    ------
    ValueError
        A map of the wrong length or with entries off Y, wrong mesh shapes.
    SpecsegError
        The library refused the meshes (zero area, non-finite coordinates).
    """
    if not _clib.has("ss_map_polish"):
        raise NotImplementedError("this libspecseg (%s) has no ss_map_polish" % library_path)
    pair = _shape_pair(VX, FX, VY, FY, map, "polish")
    if pair is not None:
        X, Y, map = pair
        VX, FX, VY, FY = X.V, X.F, Y.V, Y.F
    mx, VX, FX = _clib.as_mesh(VX, FX)
    my, VY, FY = _clib.as_mesh(VY, FY)
    m = _map_entries(map, VX.shape[0], VY.shape[0], "polish")
    nX = VX.shape[0]
    out, e = np.zeros(nX, dtype=np.int32), _err()
    _check(_clib.compute(lib.ss_map_polish, C.byref(mx), C.byref(my), _clib.ptr(m, C.c_int), None,
                         _clib.ptr(out, C.c_int), C.byref(e)), e)
    return out


class Shape:
    """A prepared shape: what `match` needs from one shape, computed once (`prepare`) or read from a
    prepared-shape file (`Shape.load`, written by `save` or ``specseg prepare``): the mesh, its
    segmentation (with the streamlined work mesh), k Laplace-Beltrami eigenpairs and the masses, and
    for one-component meshes the landmark-free pairing's signature. The file format is the C
    library's (versioned and checksummed); a damaged or other-version file raises SpecsegError.

    Attributes
    ----------
    V : numpy.ndarray of float64, shape (n, 3)
        The input mesh's vertices (a copy).
    F : numpy.ndarray of int32, shape (m, 3)
        Its triangles.
    n : int
        Vertex count.
    k : int
        Eigenpairs it carries (a match needs `k_needed`).
    labels : numpy.ndarray of int32, shape (n,)
        The segment of each vertex (as `segment`).
    centers : numpy.ndarray of int32, shape (s,)
        The input vertex at the centre of each segment.
    eigenvalues : numpy.ndarray of float64, shape (k,)
    has_signature : bool
        Whether the landmark-free pairing's signature is stored.
    """

    def __init__(self):
        self._s = _clib.ss_prepared_shape()
        self._live = False

    def _check(self):
        if not self._live:
            raise ValueError("this Shape holds nothing (use specseg.prepare or Shape.load)")

    @classmethod
    def load(cls, path):
        """The prepared shape in the file at `path` (SpecsegError when missing, damaged or of another
        format version)."""
        if not _clib.has("ss_prepared_shape_read"):
            raise NotImplementedError("this libspecseg (%s) has no prepared shapes" % library_path)
        sh, e = cls(), _err()
        _check(lib.ss_prepared_shape_read(os.fsencode(path), C.byref(sh._s), C.byref(e)), e)
        sh._live = True
        return sh

    def save(self, path):
        """Writes the prepared shape to `path` (the format ``specseg match`` / ``segment`` read)."""
        self._check()
        e = _err()
        _check(lib.ss_prepared_shape_write(os.fsencode(path), C.byref(self._s), C.byref(e)), e)

    def __del__(self):
        if getattr(self, "_live", False):
            lib.ss_prepared_shape_free(C.byref(self._s))
            self._live = False

    @property
    def n(self):
        self._check()
        return self._s.mesh.nv

    def _matched(self):  # the spectrum a match uses: the proxy's for a very large mesh
        return self._s.proxy_prep if self._s.has_proxy else self._s.prep

    @property
    def k(self):
        self._check()
        return self._matched().kev

    @property
    def V(self):
        self._check()
        return np.ctypeslib.as_array(self._s.mesh.V, shape=(self._s.mesh.nv, 3)).copy()

    @property
    def F(self):
        self._check()
        return np.ctypeslib.as_array(self._s.mesh.F, shape=(self._s.mesh.nf, 3)).copy()

    @property
    def labels(self):
        self._check()
        return _clib.copy_array(self._s.prep.seg.labels, self._s.prep.seg.nv, np.int32)

    @property
    def centers(self):
        self._check()
        return _clib.copy_array(self._s.prep.seg.centers, self._s.prep.seg.m, np.int32)

    @property
    def eigenvalues(self):
        self._check()
        p = self._matched()  # of the proxy, for a mesh matched through one (has_proxy)
        return _clib.copy_array(p.evals, p.kev, np.float64)

    @property
    def has_signature(self):
        self._check()
        return bool(self._s.has_signature)

    @property
    def has_proxy(self):
        """True for a very large mesh (above 100,000 vertices) matched through a coarse proxy, as
        `match` matches its mesh; `labels` / `centers` stay the mesh's own segmentation."""
        self._check()
        return bool(self._s.has_proxy)

    def __repr__(self):
        if not self._live:
            return "Shape(empty)"
        return "Shape(n=%d, k=%d, segments=%d%s)" % (self.n, self.k, self._s.prep.seg.m,
                                                     ", signature" if self.has_signature else "")


def k_needed(landmarks=True, k=None, zoomout=None):
    """Eigenpairs a prepared shape needs for `match` with these options (the default: 150, with
    landmarks or without, where the map kept among the hypotheses is refined further; a Shape with
    fewer but at least 110 is matched too, that refinement stopping at its eigenpairs, with a note).

    Parameters
    ----------
    landmarks : bool, optional
        Whether the match has landmarks (False: landmark-free, which also needs the pairing's).
    k : int, optional
        The match's basis size (library default 50).
    zoomout : int, optional
        The match's ZoomOut size (library default 110).

    Returns
    -------
    int

    Raises
    ------
    ValueError
        k or zoomout outside the int32 range.
    """
    o = _clib.ss_match_options()
    lib.ss_match_default_options(C.byref(o))
    if k is not None:
        o.fmap.k = _as_int32(k, "k")
    if zoomout is not None:
        o.fmap.zoomout_kmax = _as_int32(zoomout, "zoomout")
    return lib.ss_match_eigenpairs(C.byref(o), 1 if landmarks else 0)


def prepare(V, F, k=None, target_faces=None, no_streamline=False, signature=True):
    """Prepares a shape once for many matches (``specseg prepare``): segmentation, k eigenpairs, masses
    and (one component) the landmark-free pairing's signature.

    Parameters
    ----------
    V : array_like of float, shape (n, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles, 0-based vertex indices.
    k : int, optional
        Eigenpairs, 3 <= k < n (default: what the default landmark-free `match` needs, 150; 110 is
        what a match with landmarks needs).
    target_faces : int, optional
        The segmentation's remeshing target (library default 15000).
    no_streamline : bool, optional
        Segment straight on the input.
    signature : bool, optional
        Compute the landmark-free pairing's signature (default True).

    Returns
    -------
    Shape

    Raises
    ------
    ValueError
        Wrong shapes, face indices out of range.
    SpecsegError
        The library refused the mesh (e.g. one its sanitizer would change) or k, or a stage failed.
    """
    if not _clib.has("ss_prepared_shape_compute"):
        raise NotImplementedError("this libspecseg (%s) has no prepared shapes" % library_path)
    m, V, F = _clib.as_mesh(V, F)
    so = _clib.ss_segment_options()
    lib.ss_segment_default_options(C.byref(so))
    if target_faces is not None:
        so.target_faces = _as_int32(target_faces, "target_faces")
    so.no_streamline = 1 if no_streamline else 0
    o = _clib.ss_match_options()
    lib.ss_match_default_options(C.byref(o))
    kev = lib.ss_match_eigenpairs(C.byref(o), 0) if k is None else _as_int32(k, "k")
    sh, e = Shape(), _err()
    _check(_clib.compute(lib.ss_prepared_shape_compute, C.byref(m), C.byref(so), kev,
                         C.byref(o.autopair) if signature else None, C.byref(sh._s), C.byref(e)), e)
    sh._live = True
    return sh


Pairing = namedtuple("Pairing", "pairs_x pairs_y centers_x centers_y energy gap mirror mirror_other confident exact "
                                 "alternative")
Pairing.__doc__ = """The result of `pair`.

Attributes
----------
pairs_x, pairs_y : numpy.ndarray of int32, shape (p,)
    Paired segments: segment pairs_x[i] of X with segment pairs_y[i] of Y.
centers_x, centers_y : numpy.ndarray of int32, shape (p,)
    The paired segments' centres (input vertices), usable as landmarks for `match`.
energy : numpy.ndarray of float64, shape (p,)
    Each pair's share of the pairing energy (lower is better).
gap : float
    (E of the best pairing other than the answer and its mirror - E) / E.
mirror, mirror_other : float
    Orientation scores (+1 preserving, -1 reversing) of the answer's and its mirror's maps.
confident : bool
    gap and orientation margin above the library's thresholds.
exact : bool
    Exact search (else the Hungarian + local moves relaxation).
alternative : bool
    A near-tie pairing (within 3 % of the best energy) replaced the search's best because its map
    preserves orientation clearly better (e.g. two torso saddles the energy could not tell apart).
"""


def pair(VX, FX, VY, FY):
    """Landmark-free pairing of the coherent segments of X and Y, as ``specseg pair``.

    Parameters
    ----------
    VX, FX, VY, FY : array_like
        The two meshes (vertices (n, 3) float, triangles (m, 3) int), consistently oriented.

    Returns
    -------
    Pairing

    Raises
    ------
    ValueError
        Wrong shapes or face indices out of range.
    SpecsegError
        The library refused a mesh or a stage failed.
    NotImplementedError
        The loaded library has no ss_pair_auto.
    """
    if not _clib.has("ss_pair_auto"):
        raise NotImplementedError("this libspecseg (%s) has no ss_pair_auto" % library_path)
    mx, VX, FX = _clib.as_mesh(VX, FX)
    my, VY, FY = _clib.as_mesh(VY, FY)
    pr, info, e = _clib.ss_segment_pairs(), _clib.ss_autopair_info(), _err()
    cx, cy = C.POINTER(C.c_int)(), C.POINTER(C.c_int)()
    st = _clib.compute(lib.ss_pair_auto, C.byref(mx), C.byref(my), None, C.byref(pr), C.byref(cx), C.byref(cy),
                       C.byref(info), C.byref(e))
    try:
        _check(st, e)
        cp = _clib.copy_array
        return Pairing(pairs_x=cp(pr.sx, pr.n, np.int32), pairs_y=cp(pr.sy, pr.n, np.int32),
                       centers_x=cp(cx, pr.n, np.int32), centers_y=cp(cy, pr.n, np.int32),
                       energy=cp(pr.energy, pr.n, np.float64), gap=info.gap, mirror=info.mirror,
                       mirror_other=info.mirror_other, confident=bool(info.confident), exact=bool(info.exact),
                       alternative=bool(info.alternative))
    finally:
        lib.ss_segment_pairs_free(C.byref(pr))
        _libc_free(cx)
        _libc_free(cy)


def _libc_free(p):
    if p:
        f = C.CDLL(None).free
        f.argtypes = [C.c_void_p]
        f(C.cast(p, C.c_void_p))


def error(map, VY, FY, gt=None, sym=None):
    """Geodesic error of a point map X -> Y (paper §6).

    e_x = d_Y(map[x], gt[x]) / sqrt(area(Y)) with exact geodesics; with `sym` (a symmetry map of X)
    the smaller of the errors to gt[x] and gt[sym[x]].

    Parameters
    ----------
    map : array_like of int, shape (nX,)
        The map: vertex of Y (0..nY-1) for each vertex of X.
    VY : array_like of float, shape (nY, 3)
        Vertex coordinates of Y.
    FY : array_like of int, shape (mY, 3)
        Triangles of Y, 0-based vertex indices.
    gt : array_like of int, shape (nX,), optional
        The ground-truth map, entries in 0..nY-1; None: the identity (then nX <= nY).
    sym : array_like of int, shape (nX,), optional
        A symmetry map of X (entries in 0..nX-1), for the symmetric error.

    Returns
    -------
    errors : numpy.ndarray of float64, shape (nX,)
        The per-vertex errors.
    mean : float
        Their mean.

    Raises
    ------
    ValueError
        An entry of map or gt outside 0..nY-1 or of sym outside 0..nX-1 (in particular one that
        does not fit an int32), mismatched lengths, nX > nY with the identity ground truth, wrong
        shapes or face indices out of range.
    SpecsegError
        The library refused the mesh.
    NotImplementedError
        The loaded library has no ss_map_geodesic_error.
    """
    if not _clib.has("ss_map_geodesic_error"):
        raise NotImplementedError("this libspecseg (%s) has no ss_map_geodesic_error" % library_path)
    my, VY, FY = _clib.as_mesh(VY, FY)
    mp = _as_int32_array(map, "map", 0, VY.shape[0] - 1).ravel()
    n = mp.size
    if gt is None and n > VY.shape[0]:
        raise ValueError("identity ground truth needs a map with at most %d entries (got %d)" % (VY.shape[0], n))
    g = None if gt is None else _indices(gt, n, "gt", VY.shape[0])
    s = None if sym is None else _indices(sym, n, "sym", n)
    errs, mean, e = np.zeros(n), C.c_double(0), _err()
    _check(lib.ss_map_geodesic_error(C.byref(my), n, _clib.ptr(mp, C.c_int), _clib.ptr(g, C.c_int),
                                    _clib.ptr(s, C.c_int), _clib.ptr(errs, C.c_double), C.byref(mean),
                                    C.byref(e)), e)
    return errs, mean.value


def align_labels(labels, ref):
    """Renumber the segment ids of `labels` to agree with `ref` where they overlap most, as
    ``specseg render --match-colors`` does (so corresponding segments get the same colour).

    Greedy on the overlap counts, each reference id used once; segments left without a partner get
    ids after the reference's largest.

    Parameters
    ----------
    labels : array_like of int, shape (n,)
        Segment id of each vertex, >= -1 (-1: none).
    ref : array_like of int, shape (n,)
        Reference segment ids of the same vertices, >= -1.

    Returns
    -------
    numpy.ndarray of int32, shape (n,)
        The renumbered labels (a new array).

    Raises
    ------
    ValueError
        Different lengths, or ids below -1 or beyond the int32 range.
    ImportError
        The render library (libspecseg_render) could not be loaded.
    """
    rl = _clib.need_render("align_labels")
    lab = np.array(_as_int32_array(labels, "labels", -1), dtype=np.int32).ravel()  # a copy: renumbered in place
    r = _as_int32_array(ref, "ref", -1).ravel()
    if r.size != lab.size:
        raise ValueError("labels and ref must have the same length (got %d and %d)" % (lab.size, r.size))
    e = _err()
    _check(rl.ss_labels_align(_clib.ptr(lab, C.c_int), _clib.ptr(r, C.c_int), lab.size, C.byref(e)), e)
    return lab


def label_colors(labels):
    """The colours ``specseg render --labels`` draws segment labels with.

    Parameters
    ----------
    labels : array_like of int, shape (n,)
        Segment labels (any int32; negative ones are grey).

    Returns
    -------
    numpy.ndarray of uint8, shape (n, 3)
        One RGB colour per label.

    Raises
    ------
    ValueError
        A label outside the int32 range.
    ImportError
        The render library (libspecseg_render) could not be loaded.
    """
    rl = _clib.need_render("label_colors")
    labels = _as_int32_array(labels, "labels").ravel()
    uniq, inv = np.unique(labels, return_inverse=True)
    table = np.zeros((uniq.size, 3), np.uint8)
    for i, l in enumerate(uniq):
        c = (C.c_ubyte * 3)()
        rl.ss_label_color(int(l), c)
        table[i] = tuple(c)
    return table[inv.ravel()] if labels.size else np.zeros((0, 3), np.uint8)


_UPS = {"x": 1, "y": 2, "z": 3, "-x": -1, "-y": -2, "-z": -3}
_VIEWS = {"front": (0, 0), "back": (180, 0), "left": (90, 0), "right": (-90, 0), "top": (0, 90), "bottom": (0, -90)}


def render(V, F, labels=None, vertex_rgb=None, face_rgb=None, scalar=None, isolines=0, markers=None,
           size=(800, 800), view="front", supersample=2, background=(255, 255, 255), up="y"):
    """A software-rendered picture of the mesh (orthographic, z-buffer, Blinn-Phong headlight).

    Parameters
    ----------
    V : array_like of float, shape (n, 3)
        Vertex coordinates.
    F : array_like of int, shape (m, 3)
        Triangles as 0-based vertex indices.
    labels : array_like of int, shape (n,), optional
        Segment of each vertex (-1: none); faces coloured as ``specseg render --labels`` (faces
        whose corners disagree drawn neutral grey). Wins over vertex_rgb and face_rgb.
    vertex_rgb : array_like of int, shape (n, 3), optional
        Per-vertex colours 0..255, interpolated over the faces.
    face_rgb : array_like of int, shape (m, 3), optional
        Per-face colours 0..255; wins over vertex_rgb. Grey when neither is given.
    scalar : array_like of float, shape (n,), optional
        A per-vertex field whose isolines are drawn (colour the surface yourself through
        vertex_rgb); non-finite values are left out of its range.
    isolines : int, optional
        Number of isoline levels of `scalar`, evenly spaced inside its range (default 0).
    markers : array_like of float, shape (p, 3), optional
        Centres of small black spheres (finite coordinates).
    size : (int, int), optional
        (width, height) of the image in pixels (default (800, 800)).
    view : str or (float, float), optional
        "front" (default), "back", "left", "right", "top", "bottom", or (azimuth, elevation) in
        degrees (finite).
    supersample : int, optional
        Anti-aliasing: s x s samples per pixel, 1..4 (default 2).
    background : (int, int, int), optional
        Background colour, each 0..255 (default white).
    up : str, optional
        The axis drawn upwards: "x", "y" (default), "z", "-x", "-y", "-z", or "auto" (the rule of
        ``specseg render``, ss_render_guess_up: +z for TOSCA, +y for FAUST).

    Returns
    -------
    numpy.ndarray of uint8, shape (height, width, 3)
        The image, top row first.

    Raises
    ------
    ValueError
        Wrong shapes, an unknown view, colours outside 0..255, labels or integer options outside
        the int32 range, non-finite view angles or markers, face indices out of range.
    SpecsegError
        The library refused the options (e.g. a non-positive size, supersample outside 1..4).
    ImportError
        The render library (libspecseg_render) could not be loaded.
    """
    rl = _clib.need_render("render")
    m, V, F = _clib.as_mesh(V, F)
    n, nf = V.shape[0], F.shape[0]
    if isinstance(view, str):
        if view not in _VIEWS:
            raise ValueError("view must be one of %s or (azimuth, elevation) (got %r)" % (", ".join(_VIEWS), view))
        az, el = _VIEWS[view]
    else:
        if len(view) != 2:
            raise ValueError("view must be a name or (azimuth, elevation) in degrees (got %r)" % (view,))
        az, el = _as_float(view[0], "view azimuth"), _as_float(view[1], "view elevation")
    if len(size) != 2:
        raise ValueError("size must be (width, height) (got %r)" % (size,))
    width, height = _as_int32(size[0], "size width", 1), _as_int32(size[1], "size height", 1)
    if len(background) != 3:
        raise ValueError("background must be an (r, g, b) colour (got %r)" % (background,))
    bg = _as_uint8_array(background, "background").ravel()
    if labels is not None:
        lab = _as_int32_array(labels, "labels", -1).ravel()
        if lab.size != n:
            raise ValueError("labels must have one entry per vertex (%d, got %d)" % (n, lab.size))
        face_rgb = np.zeros((nf, 3), np.uint8)
        e = _err()
        _check(rl.ss_segmentation_face_colors(C.byref(m), _clib.ptr(lab, C.c_int), None,
                                             _clib.ptr(face_rgb, C.c_ubyte), C.byref(e)), e)
    fr = None if face_rgb is None else _as_uint8_array(face_rgb, "face_rgb")
    vr = None if vertex_rgb is None else _as_uint8_array(vertex_rgb, "vertex_rgb")
    if fr is not None and fr.shape != (nf, 3):
        raise ValueError("face_rgb must be (m, 3), m = %d (got shape %s)" % (nf, fr.shape))
    if vr is not None and vr.shape != (n, 3):
        raise ValueError("vertex_rgb must be (n, 3), n = %d (got shape %s)" % (n, vr.shape))
    sc = _clib.ss_render_scene()
    rl.ss_render_scene_init(C.byref(sc), C.byref(m))
    sc.vertex_rgb, sc.face_rgb = _clib.ptr(vr, C.c_ubyte), _clib.ptr(fr, C.c_ubyte)
    sv = None
    if scalar is not None:
        sv = _as_float64_array(scalar, "scalar").ravel()
        if sv.size != n:
            raise ValueError("scalar must have one entry per vertex (%d, got %d)" % (n, sv.size))
        sc.scalar, sc.isolines = _clib.ptr(sv, C.c_double), _as_int32(isolines, "isolines", 0)
    mk = None
    if markers is not None:
        mk = _as_float64_array(markers, "markers", finite=True)
        if mk.size % 3:
            raise ValueError("markers must be a (p, 3) array of points (got shape %s)" % (mk.shape,))
        mk = mk.reshape(-1, 3)
        sc.nmarkers, sc.markers = mk.shape[0], _clib.ptr(mk, C.c_double)
    o = _clib.ss_render_options()
    rl.ss_render_default_options(C.byref(o))
    o.width, o.height = width, height
    o.azimuth, o.elevation = az, el
    o.supersample = _as_int32(supersample, "supersample")
    if up == "auto":
        meshes = (C.POINTER(_clib.ss_mesh) * 1)(C.pointer(m))
        o.up = rl.ss_render_guess_up(meshes, 1)
    elif up in _UPS:
        o.up = _UPS[up]
    else:
        raise ValueError("up must be one of %s or 'auto' (got %r)" % (", ".join(_UPS), up))
    for c in range(3):
        o.background[c] = int(bg[c])
    img, e = np.zeros((height, width, 3), np.uint8), _err()
    _check(rl.ss_render(C.byref(sc), C.byref(o), _clib.ptr(img, C.c_ubyte), C.byref(e)), e)
    return img


def write_png(path, img):
    """Write an RGB image as an 8-bit PNG file.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    img : array_like of int, shape (height, width, 3)
        The image, top row first, values 0..255 (e.g. what `render` returns).

    Returns
    -------
    None

    Raises
    ------
    ValueError
        Not an (H, W, 3) array, or values outside 0..255.
    SpecsegError
        The file cannot be written, or the library was built without PNG support.
    ImportError
        The render library (libspecseg_render) could not be loaded.
    """
    rl = _clib.need_render("write_png")
    img = _as_uint8_array(img, "img")
    if img.ndim != 3 or img.shape[2] != 3:
        raise ValueError("img must be an (H, W, 3) uint8 array (got shape %s)" % (img.shape,))
    if img.shape[0] > _clib.INT32_MAX or img.shape[1] > _clib.INT32_MAX:
        raise ValueError("img is too large for PNG (%d x %d)" % (img.shape[1], img.shape[0]))
    e = _err()
    _check(rl.ss_write_png(os.fsencode(path), _clib.ptr(img, C.c_ubyte), img.shape[1], img.shape[0], C.byref(e)), e)
