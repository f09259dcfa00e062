#!/usr/bin/env python3
"""`specseg refine` against pyFM's ZoomOut on the same rough maps, run side by side: the CPU of each
refinement (rounds interleaved, the order rotating from round to round, one thread each, medians and
their ratio) and the accuracy of both on the benchmark's ground truth (`specseg eval --benchmark
--maps`: the rough maps, ours refined, pyFM's refined, one table).

  scripts/bench_refine.py SPECSEG --benchmark DIR --maps ROUGHDIR --pyfm PYFMDIR --out OUTDIR
                          [--pairs FILE] [--first N] [--rounds R] [--cache DIR] [--k 50] [--kmax 110]
                          [--step 5] [--samples 1000]

ROUGHDIR: the maps to refine, X__Y.txt (line i = the vertex of Y for vertex i of X, 0-based), e.g.
`specseg match --no-refine` maps or another method's (scripts/bench_pyfm_maps.py --kmax 35 gives
pyFM's unrefined ones). The pairs: --pairs FILE, else DIR/test_pairs.txt; pairs without a rough map
are left out. specseg: `SPECSEG refine X.sss Y.sss MAP --k K --zoomout KMAX --zoomout-step STEP
--zoomout-samples SAMPLES`, process CPU from getrusage, on prepared shapes (--cache DIR: the eval
cache's NAME_<key>.sss when there is exactly one; else `specseg prepare` into OUTDIR/sss, not timed).
pyFM (github.com/RobinMagnet/pyFM, a local source tree: never vendored): its meshes processed once
(area-normalised, KMAX + 30 eigenpairs, not timed), then per pair, timed with time.process_time():
mesh_zoomout_refine_p2p(rough map, k_init K, nit (KMAX - K) / STEP, step STEP, subsample: SAMPLES
Euclidean farthest points of each mesh (extract_fps, timed; its geodesic ones need potpourri3d),
return_p2p) -- its counterpart of the same refinement.
Outputs: OUTDIR/specseg/X__Y.txt, OUTDIR/pyfm/X__Y.txt (the first round's maps), OUTDIR/score (the
benchmark's table, pairs.csv and summary.json)."""
import argparse
import glob
import os
import resource
import statistics
import subprocess
import sys
import time


def cpu_of(cmd, env):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("specseg")
    ap.add_argument("--benchmark", required=True)
    ap.add_argument("--maps", required=True)
    ap.add_argument("--pyfm", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--pairs", default=None)
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--cache", default=None)
    ap.add_argument("--k", type=int, default=50)
    ap.add_argument("--kmax", type=int, default=110)
    ap.add_argument("--step", type=int, default=5)
    ap.add_argument("--samples", type=int, default=1000)
    a = ap.parse_args()
    if not os.path.isdir(os.path.join(a.pyfm, "pyFM")):
        sys.exit("--pyfm %s: no pyFM/ in it" % a.pyfm)
    if a.kmax <= a.k or (a.kmax - a.k) % a.step:
        sys.exit("--kmax must exceed --k by a multiple of --step (pyFM's nit)")
    # single-threaded numpy / BLAS here and in specseg: set before numpy is first imported
    os.environ["OMP_NUM_THREADS"] = os.environ["OPENBLAS_NUM_THREADS"] = "1"
    env = dict(os.environ)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import bench_pyfm_maps as bpm
    import numpy as np

    _, TriMesh = bpm.import_pyfm(a.pyfm)  # puts the pyFM tree on the path
    from pyFM.refine.zoomout import mesh_zoomout_refine_p2p
    md = bpm.mesh_dir(a.benchmark)
    pfile = a.pairs or next((c for c in (os.path.join(a.benchmark, "test_pairs.txt"), os.path.join(md, "test_pairs.txt"))
                             if os.path.isfile(c)), None)
    if pfile is None:
        sys.exit("no pairs: give --pairs FILE")
    pairs = [(x, y) for x, y in bpm.read_pairs(pfile) if os.path.isfile(os.path.join(a.maps, "%s__%s.txt" % (x, y)))]
    if a.first > 0:
        pairs = pairs[: a.first]
    if not pairs:
        sys.exit("no pair of %s has a map in %s" % (pfile, a.maps))
    for d in ("specseg", "pyfm", "sss"):
        os.makedirs(os.path.join(a.out, d), exist_ok=True)
    names = sorted({n for p in pairs for n in p})
    sss = {}
    for n in names:  # prepared shapes, not timed
        hits = glob.glob(os.path.join(a.cache, n + "_*.sss")) if a.cache else []
        if len(hits) == 1:
            sss[n] = hits[0]
            continue
        sss[n] = os.path.join(a.out, "sss", n + ".sss")
        if not os.path.isfile(sss[n]):
            subprocess.run([a.specseg, "prepare", os.path.join(md, n + ".off"), "-o", sss[n], "-k", str(a.kmax)],
                           check=True, env=env, stdout=subprocess.DEVNULL)
    t0 = time.process_time()
    meshes = {n: bpm.process_mesh(TriMesh, os.path.join(md, n + ".off"), a.kmax) for n in names}
    mesh_cpu = time.process_time() - t0
    rough = {p: np.loadtxt(os.path.join(a.maps, "%s__%s.txt" % p), dtype=np.int64).ravel() for p in pairs}
    nit = (a.kmax - a.k) // a.step

    def ours(x, y, first):
        out = os.path.join(a.out, "specseg", "%s__%s.txt" % (x, y)) if first else os.path.join(a.out, "specseg", "last.txt")
        return cpu_of([a.specseg, "refine", sss[x], sss[y], os.path.join(a.maps, "%s__%s.txt" % (x, y)), "-o", out,
                       "--k", str(a.k), "--zoomout", str(a.kmax), "--zoomout-step", str(a.step),
                       "--zoomout-samples", str(a.samples)], env)

    def pyfm(x, y, first):
        t = time.process_time()
        # mesh1 = Y, mesh2 = X: p2p_21 sends X's vertices to Y, FM_12 maps functions on Y to X; the
        # samples by Euclidean farthest points (its geodesic ones need potpourri3d), timed as ours are
        sub = (meshes[y].extract_fps(a.samples, random_init=False, geodesic=False),
               meshes[x].extract_fps(a.samples, random_init=False, geodesic=False))
        _, p2p = mesh_zoomout_refine_p2p(rough[(x, y)], meshes[y], meshes[x], a.k, nit=nit, step=a.step,
                                         subsample=sub, return_p2p=True)
        cpu = time.process_time() - t
        if first:
            np.savetxt(os.path.join(a.out, "pyfm", "%s__%s.txt" % (x, y)), p2p, fmt="%d")
        return cpu

    variants = [("specseg refine", ours), ("pyFM ZoomOut", pyfm)]
    cpu = {name: [] for name, _ in variants}
    for r in range(a.rounds):
        for x, y in pairs:
            for name, fn in variants[r % 2:] + variants[: r % 2]:
                cpu[name].append(fn(x, y, r == 0))
    med = {name: statistics.median(v) for name, v in cpu.items()}
    for name, _ in variants:
        print("%-16s median CPU %.3f s over %d runs (%d pairs x %d rounds)" % (name, med[name], len(cpu[name]),
                                                                           len(pairs), a.rounds))
    print("ratio pyFM / specseg: %.2fx" % (med["pyFM ZoomOut"] / med["specseg refine"]))
    print("both: k %d -> %d, step %d, %d samples; pyFM's %d meshes processed once in %.2f s CPU, not timed"
          % (a.k, a.kmax, a.step, a.samples, len(meshes), mesh_cpu))
    listed = os.path.join(a.out, "pairs.txt")
    with open(listed, "w") as f:
        f.writelines("%s %s\n" % p for p in pairs)
    subprocess.run([a.specseg, "eval", "--benchmark", a.benchmark, "--pairs", listed, "--no-match",
                    "--maps", "rough=" + a.maps, "--maps", "specseg_refine=" + os.path.join(a.out, "specseg"),
                    "--maps", "pyfm_zoomout=" + os.path.join(a.out, "pyfm"), "--out", os.path.join(a.out, "score"),
                    "--quiet"], check=True, env=env)


if __name__ == "__main__":
    main()
