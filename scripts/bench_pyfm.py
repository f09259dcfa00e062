#!/usr/bin/env python3
"""Whole-match CPU time and accuracy of `specseg match` against pyFM (github.com/RobinMagnet/pyFM, a
local copy, never vendored), side by side on FAUST pairs, interleaved rounds, medians.

  scripts/bench_pyfm.py --pyfm DIR --specseg BIN --data ../shared/data [--pairs 000:011,...]
                        [--rounds 3] [--k 50] [--kmax 120] [--out DIR]

pyFM runs its notebook pipeline (examples/mesh_and_matching): TriMesh(area_normalize, center),
process(k = kmax + 30), FunctionalMapping.preprocess(n_ev = (k, k), 5 landmarks, WKS, n_descr 100,
subsample_step 5), fit(w_descr 1, w_lap 1e-2, w_dcomm 1e-1, w_orient 0), get_p2p (STD), then
zoomout_refine(step 5) to kmax (STD + ZoomOut); the STD map once more computing only k eigenpairs
(the fair reference for an unrefined map). specseg runs `specseg match X Y --landmarks LM`
with `--no-refine --probes std` (STD with its default descriptors from 100 eigenpairs and the
orientation term), the same with `--descr-k K --orient 0` (the paper's STD: descriptors from the k
eigenpairs, as pyFM's), `--no-refine` (DIFF) and its refined default, and, from shapes prepared once
(`specseg prepare`, not timed), the unrefined STD. CPU time = user +
system of every thread: pyFM's from time.process_time() in this process (reading the meshes
included), specseg's from the children's rusage. Errors: `specseg error` (exact geodesics / sqrt(area),
identity ground truth, every vertex). Prints per method the median CPU per pair, the ratio pyFM /
specseg and the mean error.
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_specseg(cmd):
    t0 = child_cpu()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return child_cpu() - t0


def mean_error(specseg, map_path, y_path):
    out = subprocess.run([specseg, "error", map_path, y_path], check=True, capture_output=True, text=True)
    for line in (out.stdout + out.stderr).splitlines():
        if line.startswith("mean_error:"):
            return float(line.split()[1])
    raise RuntimeError("no mean_error in: " + out.stdout + out.stderr)


def run_pyfm(x_path, y_path, lm, k, kmax, out_std, out_zo, kev=None):
    import numpy as np
    from pyFM.functional import FunctionalMapping
    from pyFM.mesh import TriMesh

    t0 = time.process_time()
    # pyFM's p2p_21 maps mesh2 to mesh1: mesh1 = Y, mesh2 = X gives line i = image on Y of vertex i of X
    kev = kev or kmax + 30
    m1 = TriMesh(y_path, area_normalize=True, center=True).process(k=kev, intrinsic=False)
    m2 = TriMesh(x_path, area_normalize=True, center=True).process(k=kev, intrinsic=False)
    model = FunctionalMapping(m1, m2)
    model.preprocess(n_ev=(k, k), n_descr=100, descr_type="WKS", landmarks=np.array(lm), subsample_step=5)
    model.fit(w_descr=1e0, w_lap=1e-2, w_dcomm=1e-1, w_orient=0)
    p2p_std = model.get_p2p(n_jobs=1)
    t_std = time.process_time() - t0
    np.savetxt(out_std, p2p_std, fmt="%d")
    if out_zo is None:
        return t_std, None
    model.zoomout_refine(nit=(kmax - k) // 5, step=5)
    p2p_zo = model.get_p2p(n_jobs=1)
    t_zo = time.process_time() - t0
    np.savetxt(out_std, p2p_std, fmt="%d")
    np.savetxt(out_zo, p2p_zo, fmt="%d")
    return t_std, t_zo


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pyfm", required=True, help="a pyFM source tree (the directory holding pyFM/)")
    ap.add_argument("--specseg", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--pairs", default="000:011,020:037,052:083")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--k", type=int, default=50)
    ap.add_argument("--kmax", type=int, default=120)
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    sys.path.insert(0, a.pyfm)
    # pyFM imports its optional geodesic / robust-Laplacian packages at module level; this pipeline
    # calls neither, so empty modules stand in where they are not installed
    import importlib.util
    import types
    for name in ("potpourri3d", "robust_laplacian"):
        if importlib.util.find_spec(name) is None:
            sys.modules[name] = types.ModuleType(name)
    out = a.out or tempfile.mkdtemp(prefix="bench_pyfm_")
    os.makedirs(out, exist_ok=True)
    faust = os.path.join(a.data, "faust")
    lm_path = os.path.join(faust, "landmarks_best.txt")
    lm = [int(l.split()[0]) for l in open(lm_path) if l.strip()]
    pairs = [p.split(":") for p in a.pairs.split(",")]
    mesh = lambda i: os.path.join(faust, "tr_reg_%s.off" % i)
    for i in sorted({i for p in pairs for i in p}):  # prepared once, outside the timings
        subprocess.run([a.specseg, "prepare", mesh(i), "-o", os.path.join(out, i + ".sss")], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    methods = ["pyFM STD", "pyFM STD+ZoomOut", "pyFM STD, k eigenpairs", "specseg STD", "specseg paper STD",
               "specseg DIFF", "specseg refined", "specseg STD, prepared"]
    cpu = {m: [] for m in methods}  # per pair: the median over rounds
    err = {m: [] for m in methods}
    for x, y in pairs:
        X, Y = mesh(x), mesh(y)
        runs = {m: [] for m in methods}
        files = {m: os.path.join(out, "%s_%s_%d.txt" % (x, y, j)) for j, m in enumerate(methods)}
        spec = {
            "specseg STD": [X, Y, "--no-refine", "--probes", "std"],
            # the paper's STD (descriptors from the k eigenpairs, as pyFM's, no orientation term)
            "specseg paper STD": [X, Y, "--no-refine", "--probes", "std", "--descr-k", str(a.k), "--orient", "0"],
            "specseg DIFF": [X, Y, "--no-refine"],
            "specseg refined": [X, Y],
            "specseg STD, prepared": [os.path.join(out, x + ".sss"), os.path.join(out, y + ".sss"), "--no-refine",
                                      "--probes", "std"],
        }
        for r in range(a.rounds):  # interleaved: every method once per round
            t_std, t_zo = run_pyfm(X, Y, lm, a.k, a.kmax, files["pyFM STD"], files["pyFM STD+ZoomOut"])
            runs["pyFM STD"].append(t_std)
            runs["pyFM STD+ZoomOut"].append(t_zo)
            runs["pyFM STD, k eigenpairs"].append(run_pyfm(X, Y, lm, a.k, a.kmax, files["pyFM STD, k eigenpairs"], None,
                                                           kev=a.k)[0])
            for m, args in spec.items():
                runs[m].append(run_specseg([a.specseg, "match", *args, "--landmarks", lm_path, "-o", files[m]]))
        for m in methods:
            cpu[m].append(statistics.median(runs[m]))
            err[m].append(mean_error(a.specseg, files[m], Y))
        print("pair %s -> %s: " % (x, y) + ", ".join("%s %.2f s %.4f" % (m, cpu[m][-1], err[m][-1]) for m in methods),
              flush=True)
    print("\n%d FAUST pairs (%s), BEST landmarks, %d interleaved rounds, k %d, ZoomOut to %d; OMP_NUM_THREADS=%s" %
          (len(pairs), a.pairs, a.rounds, a.k, a.kmax, os.environ.get("OMP_NUM_THREADS", "unset")))
    print("%-24s %12s %14s %12s" % ("method", "CPU / pair", "pyFM / it", "mean error"))
    ref = {"specseg STD": "pyFM STD, k eigenpairs", "specseg paper STD": "pyFM STD, k eigenpairs",
           "specseg DIFF": "pyFM STD, k eigenpairs",
           "specseg STD, prepared": "pyFM STD, k eigenpairs",
           "specseg refined": "pyFM STD+ZoomOut"}
    for m in methods:
        c = statistics.median(cpu[m])
        ratio = "%.2fx" % (statistics.median(cpu[ref[m]]) / c) if m in ref else "-"
        print("%-24s %10.3f s %14s %12.4f" % (m, c, ratio, statistics.mean(err[m])))
    print("ratios: pyFM STD computing only the k eigenpairs it uses against specseg's unrefined maps, pyFM STD +\n"
          "ZoomOut (kmax + 30 eigenpairs, its notebook's setting) against the refined default")


if __name__ == "__main__":
    main()
