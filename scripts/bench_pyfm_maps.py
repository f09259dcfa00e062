#!/usr/bin/env python3
"""pyFM's landmark-free maps for a benchmark folder, in the layout `specseg eval --benchmark --maps`
reads: MAPDIR/X__Y.txt, line i = the vertex of Y for vertex i of X (0-based). pyFM
(github.com/RobinMagnet/pyFM) runs from a local copy (--pyfm: the folder holding pyFM/), never
vendored.

  scripts/bench_pyfm_maps.py --pyfm DIR --benchmark DIR --out MAPDIR [--pairs FILE] [--first N]
                             [--k 35] [--kmax 100] [--w-orient 1]

The pairs: --pairs FILE, else the benchmark's test_pairs.txt (two names a line); --first N keeps the
first N. Per pair, pyFM's pipeline without landmarks (as its example notebook, landmarks left out):
TriMesh(area_normalize, center).process(kmax + 30 eigenpairs), FunctionalMapping(Y, X) (its p2p_21
maps X onto Y), preprocess(n_ev = (k, k), 100 WKS descriptors, subsample_step 5), fit(w_descr 1,
w_lap 1e-2, w_dcomm 1e-1, w_orient: its orientation-preserving term), ZoomOut (step 5) from k to
kmax, get_p2p. Each mesh is processed once. Maps already in MAPDIR are kept (resume). A mesh that pyFM
cannot read skips its pairs (the benchmark then reports them missing). MAPDIR/seconds.txt gets
"X Y SECONDS" per map written (CPU of the pair: descriptors, fit, ZoomOut and the point map; the meshes'
processing is reported once per mesh on stdout). Run it with OMP_NUM_THREADS / OPENBLAS_NUM_THREADS
as you want pyFM to use (e.g. 1 beside a benchmark run).

As a module (scripts/bench_hypotheses.py --pyfm times the same pipeline): import_pyfm(DIR),
process_mesh(TriMesh, PATH, kmax) and pyfm_map(FunctionalMapping, mesh_x, mesh_y, k, kmax, w_orient);
K, KMAX and W_ORIENT are the defaults.
"""
import argparse
import importlib.util
import os
import sys
import time
import types

K, KMAX, W_ORIENT = 35, 100, 1.0


def import_pyfm(pyfm_dir):
    """pyFM's FunctionalMapping and TriMesh from the source tree pyfm_dir (the folder holding pyFM/).
    Set OMP_NUM_THREADS / OPENBLAS_NUM_THREADS before calling it if numpy is not imported yet."""
    sys.path.insert(0, pyfm_dir)
    # pyFM imports its optional geodesic / robust-Laplacian packages at module level; this pipeline
    # calls neither, so empty modules stand in where they are not installed
    for name in ("potpourri3d", "robust_laplacian"):
        if importlib.util.find_spec(name) is None:
            sys.modules[name] = types.ModuleType(name)
    from pyFM.functional import FunctionalMapping
    from pyFM.mesh import TriMesh
    return FunctionalMapping, TriMesh


def process_mesh(TriMesh, path, kmax=KMAX):
    """A mesh as the pipeline needs it: read (area-normalized, centred) and kmax + 30 eigenpairs."""
    m = TriMesh(path, area_normalize=True, center=True)
    m.process(k=kmax + 30, intrinsic=False)
    return m


def pyfm_map(FunctionalMapping, mx, my, k=K, kmax=KMAX, w_orient=W_ORIENT):
    """pyFM's landmark-free map X -> Y of two processed meshes: entry i = the vertex of Y for vertex i
    of X (descriptors, fit, ZoomOut from k to kmax, point map)."""
    model = FunctionalMapping(my, mx)  # mesh1 = Y, mesh2 = X: p2p_21 sends X's vertices to Y
    model.preprocess(n_ev=(k, k), n_descr=100, descr_type="WKS", landmarks=None, subsample_step=5)
    model.fit(w_descr=1e0, w_lap=1e-2, w_dcomm=1e-1, w_orient=w_orient)
    if kmax > k:
        model.zoomout_refine(nit=(kmax - k) // 5, step=5)
    return model.get_p2p(n_jobs=1)


def mesh_dir(bench):
    for sub in ("", "vtx_5k", "off", "shapes"):
        d = os.path.join(bench, sub) if sub else bench
        if os.path.isdir(d) and any(f.endswith(".off") for f in os.listdir(d)):
            return d
    raise SystemExit("%s: no .off meshes in it (nor in its vtx_5k/, off/ or shapes/)" % bench)


def read_pairs(path):
    pairs = []
    for n, line in enumerate(open(path), 1):
        t = line.split("#")[0].split()
        if not t:
            continue
        if len(t) != 2:
            raise SystemExit("%s:%d: a pair is two names" % (path, n))
        pairs.append((t[0], t[1]))
    return pairs


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pyfm", required=True, help="a pyFM source tree (the folder holding pyFM/)")
    ap.add_argument("--benchmark", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--pairs", default=None)
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--k", type=int, default=K)
    ap.add_argument("--kmax", type=int, default=KMAX)
    ap.add_argument("--w-orient", type=float, default=W_ORIENT)
    a = ap.parse_args()
    FunctionalMapping, TriMesh = import_pyfm(a.pyfm)
    import numpy as np

    md = mesh_dir(a.benchmark)
    pfile = a.pairs
    if pfile is None:
        for c in (os.path.join(a.benchmark, "test_pairs.txt"), os.path.join(md, "test_pairs.txt")):
            if os.path.isfile(c):
                pfile = c
                break
    if pfile is None:
        raise SystemExit("no pairs: give --pairs FILE (the benchmark has no test_pairs.txt)")
    pairs = read_pairs(pfile)
    if a.first > 0:
        pairs = pairs[: a.first]
    os.makedirs(a.out, exist_ok=True)
    meshes, bad = {}, {}

    def mesh(name):
        if name in meshes or name in bad:
            return meshes.get(name)
        t0 = time.process_time()
        try:
            m = process_mesh(TriMesh, os.path.join(md, name + ".off"), a.kmax)
        except Exception as e:  # a mesh pyFM cannot read or process
            bad[name] = str(e)
            print("%s: not processed: %s" % (name, e), flush=True)
            return None
        meshes[name] = m
        print("%s: processed in %.2f s CPU" % (name, time.process_time() - t0), flush=True)
        return m

    secs = open(os.path.join(a.out, "seconds.txt"), "a")
    done = 0
    for x, y in pairs:
        path = os.path.join(a.out, "%s__%s.txt" % (x, y))
        if os.path.exists(path):
            continue
        mx, my = mesh(x), mesh(y)
        if mx is None or my is None:
            continue
        t0 = time.process_time()
        p2p = pyfm_map(FunctionalMapping, mx, my, a.k, a.kmax, a.w_orient)
        dt = time.process_time() - t0
        if len(p2p) != mx.n_vertices:
            raise SystemExit("%s -> %s: pyFM gave %d entries for %d vertices" % (x, y, len(p2p), mx.n_vertices))
        tmp = path + ".tmp"
        np.savetxt(tmp, p2p, fmt="%d")
        os.replace(tmp, path)
        secs.write("%s %s %.6f\n" % (x, y, dt))
        secs.flush()
        done += 1
        print("%s -> %s: %.2f s CPU" % (x, y, dt), flush=True)
    print("%d maps written to %s (%d pairs listed, %d meshes not processed)" % (done, a.out, len(pairs), len(bad)))


if __name__ == "__main__":
    main()
