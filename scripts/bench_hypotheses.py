#!/usr/bin/env python3
"""CPU of a landmark-free match of two shapes with the default hypotheses against one hypothesis
(the pairing's answer alone), and with --pyfm against pyFM's landmark-free pipeline, run side by
side: rounds interleaved (the order of the methods rotates from round to round), one thread each,
medians printed with their ratios.

  scripts/bench_hypotheses.py SPECSEG X1 Y1 [X2 Y2 ...] [--rounds R] [--pyfm DIR] [--skip-tol T]

X, Y: prepared shapes (.sss) or meshes; a mesh is prepared once (`SPECSEG prepare`, default
eigenpairs, into a temporary folder, not timed). specseg: process CPU (user + system) of each
`SPECSEG match X.sss Y.sss` (OMP_NUM_THREADS=1), measured with getrusage.

--skip-tol T: also the default with `--skip-tol T` (candidates whose landmarks an earlier map keeps
are not mapped), timed in the same rounds, with its ratio to the default.

--pyfm DIR (a pyFM source tree, the folder holding pyFM/; never vendored): X, Y must then be meshes
(.off or .obj, pyFM's readers). pyFM runs the pipeline of scripts/bench_pyfm_maps.py (WKS,
orientation term, ZoomOut; its k, kmax and w_orient defaults, printed) in this process with
OMP_NUM_THREADS=1 and OPENBLAS_NUM_THREADS=1. As the .sss files already hold specseg's eigenpairs,
pyFM's per-mesh processing (TriMesh load + eigenpairs) is done once and not timed; timed per pair,
with time.process_time(): the descriptors, the fit, ZoomOut and the point map.
"""
import os, resource, shutil, statistics, subprocess, sys, tempfile


def cpu_of(cmd, env):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def take_option(argv, name):
    """The value of `name VALUE` in argv (removed from it), else None."""
    if name not in argv:
        return None
    i = argv.index(name)
    if i + 1 >= len(argv):
        sys.exit(__doc__)
    value = argv[i + 1]
    del argv[i:i + 2]
    return value


def main(argv):
    rounds = 3
    r = take_option(argv, "--rounds")
    if r is not None:
        rounds = int(r)
    pyfm_dir = take_option(argv, "--pyfm")
    skip_tol = take_option(argv, "--skip-tol")
    if len(argv) < 3 or len(argv) % 2 == 0:
        sys.exit(__doc__)
    binary, shapes = argv[0], argv[1:]
    if pyfm_dir is not None:
        if not os.path.isdir(os.path.join(pyfm_dir, "pyFM")):
            sys.exit("--pyfm %s: no pyFM/ in it" % pyfm_dir)
        for s in shapes:
            if os.path.splitext(s)[1].lower() not in (".off", ".obj"):
                sys.exit("%s: with --pyfm, X and Y are meshes (.off or .obj), pyFM reads them" % s)
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    tmp = tempfile.mkdtemp()
    try:
        run(binary, shapes, rounds, pyfm_dir, skip_tol, env, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def run(binary, shapes, rounds, pyfm_dir, skip_tol, env, tmp):
    out = os.path.join(tmp, "map.txt")

    prepared = {}  # a mesh -> its prepared shape, made once (not timed)
    for s in shapes:
        if s.endswith(".sss") or s in prepared:
            continue
        sss = os.path.join(tmp, "%d_%s.sss" % (len(prepared), os.path.splitext(os.path.basename(s))[0]))
        subprocess.run([binary, "prepare", s, "-o", sss], check=True, env=env, stdout=subprocess.DEVNULL)
        prepared[s] = sss
    pairs = list(zip(shapes[0::2], shapes[1::2]))

    def specseg(extra):
        return lambda x, y: cpu_of([binary, "match", prepared.get(x, x), prepared.get(y, y), "-o", out] + extra, env)

    variants = [("default (4 hypotheses)", specseg([])), ("one hypothesis", specseg(["--hypotheses", "1"]))]
    skip_name = "--skip-tol %s" % skip_tol
    if skip_tol is not None:
        variants.append((skip_name, specseg(["--skip-tol", skip_tol])))

    if pyfm_dir is not None:
        # single-threaded numpy / BLAS in this process: set before numpy is first imported
        os.environ["OMP_NUM_THREADS"] = "1"
        os.environ["OPENBLAS_NUM_THREADS"] = "1"
        import time
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import bench_pyfm_maps as bpm
        FunctionalMapping, TriMesh = bpm.import_pyfm(pyfm_dir)
        meshes, t0 = {}, time.process_time()
        for s in shapes:  # each mesh once, not timed (as specseg's prepare)
            if s not in meshes:
                meshes[s] = bpm.process_mesh(TriMesh, s, bpm.KMAX)
        mesh_cpu = time.process_time() - t0

        def pyfm(x, y):
            t = time.process_time()
            bpm.pyfm_map(FunctionalMapping, meshes[x], meshes[y], bpm.K, bpm.KMAX, bpm.W_ORIENT)
            return time.process_time() - t

        variants.append(("pyFM", pyfm))

    cpu = {name: [] for name, _ in variants}
    n = len(variants)
    for r in range(rounds):
        for x, y in pairs:
            order = variants[r % n:] + variants[:r % n]
            for name, measure in order:
                cpu[name].append(measure(x, y))
    med = {name: statistics.median(v) for name, v in cpu.items()}
    for name, _ in variants:
        print("%-24s median CPU %.3f s over %d runs (%d pairs x %d rounds)" % (name, med[name], len(cpu[name]),
                                                                              len(pairs), rounds))
    default, one = variants[0][0], variants[1][0]
    print("ratio default / one hypothesis: %.2fx" % (med[default] / med[one]))
    if skip_tol is not None:
        print("ratio %s / default: %.2fx" % (skip_name, med[skip_name] / med[default]))
    if pyfm_dir is not None:
        print("ratio pyFM / default: %.2fx" % (med["pyFM"] / med[default]))
        print("ratio pyFM / one hypothesis: %.2fx" % (med["pyFM"] / med[one]))
        print("pyFM settings: k %d, kmax %d, w_orient %g (WKS, ZoomOut step 5); its %d meshes processed once "
              "in %.2f s CPU, not timed" % (bpm.K, bpm.KMAX, bpm.W_ORIENT, len(meshes), mesh_cpu))


if __name__ == "__main__":
    main(sys.argv[1:])
