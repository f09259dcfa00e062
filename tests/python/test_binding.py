"""The Python binding gives the CLI's results on the same input (issue 7).

usage: test_binding.py SPECSEG_BIN MESH WORKDIR [--no-match]
Runs `specseg eigs / geodesic / segment / error / match` and the binding's eigs / geodesic / segment /
error / match on MESH and compares; also laplacian invariants, rendering and error reporting.
Prints "N passed, N failed" like the C tests and exits 1 on any failure."""
import base64
import json
import math
import os
import subprocess
import sys

import numpy as np

import specseg

BIN, MESH, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
NO_MATCH = "--no-match" in sys.argv
passed = failed = 0


def check(cond, what):
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what, file=sys.stderr)


def cli(*args):
    r = subprocess.run([BIN] + [str(a) for a in args], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("specseg %s failed (%d): %s" % (" ".join(map(str, args)), r.returncode, r.stderr))
    return r.stdout


def path(name):
    return os.path.join(WORK, name)


print("library:", specseg.library_path)
V, F = specseg.read_mesh(MESH)
n = V.shape[0]
check(V.dtype == np.float64 and F.dtype == np.int32 and V.shape[1] == 3 and F.shape[1] == 3, "read_mesh types")

# --- laplacian: symmetric, constants in the kernel, masses sum to the area ---
W, M = specseg.laplacian(V, F)
if isinstance(W, tuple):
    indptr, indices, data = W
    check(indptr.size == n + 1 and indices.size == data.size, "CSC triple sizes")
else:
    Wd = W
    check(abs(Wd - Wd.T).max() < 1e-12, "W symmetric")
    check(np.abs(Wd @ np.ones(n)).max() < 1e-9 * abs(Wd).max(), "W 1 = 0")
a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
check(abs(M.sum() - area) < 1e-9 * area, "sum M = area")

# --- eigs: same eigenvalues (printed %.17g) and eigenvectors up to sign ---
K = 8
out = cli("eigs", MESH, "-k", K, "--evecs", path("evecs.npy"))
ev_cli = np.array([float(x) for x in out.split()])
Xc = np.load(path("evecs.npy"))
ev, X = specseg.eigs(V, F, K)
check(ev_cli.shape == (K,) and np.allclose(ev, ev_cli, rtol=1e-10, atol=1e-12), "eigs: eigenvalues %s vs %s" % (ev, ev_cli))
sgn = np.sign(np.sum(X * Xc, axis=0))
check(Xc.shape == X.shape and np.abs(X * sgn - Xc).max() < 1e-8, "eigs: eigenvectors")

# --- geodesic: exact and graph distances, two sources ---
src = [0, n // 2]
for method in ("exact", "graph"):
    cli("geodesic", MESH, "--source", src[0], "--source", src[1], "--method", method, "-o", path("d.txt"))
    dc = np.loadtxt(path("d.txt"))
    d = specseg.geodesic(V, F, src, method=method)
    check(dc.shape == d.shape and np.array_equal(np.isinf(d), np.isinf(dc)), "geodesic %s: shape / inf" % method)
    fin = np.isfinite(d)
    check(np.abs(d[fin] - dc[fin]).max() <= 1e-12 * max(1.0, d[fin].max()), "geodesic %s: values" % method)
    check(d[src[0]] == 0 and d[src[1]] == 0, "geodesic %s: zero at the sources" % method)

# --- segment: identical labels and centres ---
cli("segment", MESH, "-o", path("labels.txt"), "--centers", path("centers.txt"))
lab_c = np.loadtxt(path("labels.txt"), dtype=np.int64, ndmin=1)
cen_c = np.loadtxt(path("centers.txt"), dtype=np.int64, ndmin=1)
seg = specseg.segment(V, F)
check(np.array_equal(seg.labels, lab_c), "segment: labels")
check(np.array_equal(seg.centers, cen_c), "segment: centers")
check(seg.m == cen_c.size and seg.labels.max() == seg.m - 1, "segment: count")
check(seg.phi.shape == (seg.work_V.shape[0],) and seg.psi.shape == (n,), "segment: work arrays")

# --- error: a map that moves some vertices to a neighbour ---
mp = np.arange(n, dtype=np.int32)
mp[F[::7, 0]] = F[::7, 1]
np.savetxt(path("map.txt"), mp, fmt="%d")
out = cli("error", path("map.txt"), MESH, "-o", path("e.txt"))
ec = np.loadtxt(path("e.txt"))
e, mean = specseg.error(mp, V, F)
check(np.allclose(e, ec, rtol=0, atol=1e-12), "error: per-vertex errors")
mean_cli = float(out.split(":")[1])
check(abs(mean - mean_cli) < 1e-6 and mean > 0, "error: mean %g vs %g" % (mean, mean_cli))
e0, m0 = specseg.error(np.arange(n), V, F)
check(m0 == 0 and not e0.any(), "error: identity map is exact")

# --- match ---
if NO_MATCH or not hasattr(specseg.lib, "ss_match"):
    print("SKIP: match comparison (%s)" % ("--no-match" if NO_MATCH else "no ss_match in the library"))
else:
    lm = [int(x) for x in np.linspace(0, n - 1, 5)]
    np.savetxt(path("lm.txt"), lm, fmt="%d")
    cli("match", MESH, MESH, "--landmarks", path("lm.txt"), "--k", 20, "-o", path("m.txt"))
    mc = np.loadtxt(path("m.txt"), dtype=np.int64)
    r = specseg.match(V, F, V, F, lm, k=20)
    check(np.array_equal(r.map, mc), "match: map")
    # the map kept among the hypotheses (beside the landmarks) is refined further, to 150 by default
    check(r.C.shape == (150, 150), "match: C shape %s, want (150, 150)" % (r.C.shape,))
    cli("match", MESH, MESH, "--landmarks", path("lm.txt"), "--k", 20, "--segment-profile", "soft", "-o", path("ms.txt"))
    ms = np.loadtxt(path("ms.txt"), dtype=np.int64)
    rs = specseg.match(V, F, V, F, lm, k=20, segment_profile="soft")
    check(np.array_equal(rs.map, ms), "match: map with the soft segment profile")
    # own descriptors: the kept WKS columns (k = 20, as the match's basis) with wks=False give the same map
    Wd = specseg.wks(V, F, k=20)[:, ::5]
    rd = specseg.match(V, F, V, F, lm, k=20, descriptors=(Wd, Wd), wks=False)
    check(np.mean(rd.map == r.map) >= 0.999, "match: the WKS as own descriptors with wks=False")
    np.save(path("wd.npy"), Wd)
    cli("match", MESH, MESH, "--landmarks", path("lm.txt"), "--k", 20, "--descriptors", path("wd.npy"), path("wd.npy"),
        "-o", path("md.txt"))
    md = np.loadtxt(path("md.txt"), dtype=np.int64)
    check(np.array_equal(specseg.match(V, F, V, F, lm, k=20, descriptors=(Wd, Wd)).map, md),
          "match: descriptors beside the WKS as the CLI's --descriptors")
    for bad in (dict(wks=False), dict(descriptors=(Wd, Wd[:, :2])), dict(descriptors=(Wd[:5], Wd))):
        try:
            specseg.match(V, F, V, F, lm, k=20, **bad)
            check(False, "match: %s accepted" % list(bad))
        except ValueError:
            check(True, "")
    try:
        specseg.match(V, F, V, F, lm, k=20, segment_profile="round")
        check(False, "match: unknown segment profile accepted")
    except ValueError:
        check(True, "match: unknown segment profile refused")
    # the orientation term's weight, as the CLI's --orient (0: the paper's Eq. (1) without it)
    cli("match", MESH, MESH, "--landmarks", path("lm.txt"), "--k", 20, "--orient", 0, "-o", path("mo.txt"))
    mo = np.loadtxt(path("mo.txt"), dtype=np.int64)
    check(np.array_equal(specseg.match(V, F, V, F, lm, k=20, orient=0).map, mo), "match: orient=0 as the CLI's --orient 0")
    for bad in (-1.0, float("nan"), 1e300):
        try:
            specseg.match(V, F, V, F, lm, k=20, orient=bad)
            check(False, "match: orient=%r accepted" % bad)
        except ValueError:
            check(True, "")

# --- prepared shapes: prepare once, match many (the same map as from the arrays and the CLI) ---
if NO_MATCH or not hasattr(specseg.lib, "ss_prepared_shape_compute"):
    print("SKIP: prepared shapes (%s)" % ("--no-match" if NO_MATCH else "no ss_prepared_shape_compute"))
else:
    # the default prepare fits the default match, landmark-free or with landmarks (the further
    # refinement of the map kept needs 150 in both; 110 without the hypotheses beside landmarks); with
    # exactly what the landmark match needs, a Shape gives the very map of the arrays
    Sd = specseg.prepare(V, F)
    check(Sd.n == n and Sd.k == specseg.k_needed(landmarks=False) == 150 and specseg.k_needed() == 150,
          "prepare: %r" % Sd)
    S = specseg.prepare(V, F, k=specseg.k_needed())
    check(S.n == n and S.k == 150 and np.array_equal(S.V, V) and np.array_equal(S.F, F), "prepare: %r" % S)
    check(np.array_equal(Sd.labels, S.labels), "prepare: the segmentation does not depend on k")
    check(np.array_equal(S.labels, seg.labels) and np.array_equal(S.centers, seg.centers), "prepare: the segmentation")
    rp = specseg.match(S, S, lm, k=20)
    check(np.array_equal(rp.map, r.map) and np.array_equal(rp.C, r.C), "match(Shape, Shape): the map from the arrays")
    S.save(path("s.sss"))
    S2 = specseg.Shape.load(path("s.sss"))
    check(np.array_equal(specseg.match(S2, S2, landmarks=lm, k=20).map, r.map), "Shape.save / load: the same map")
    cli("match", path("s.sss"), path("s.sss"), "--landmarks", path("lm.txt"), "--k", 20, "-o", path("mp.txt"))
    check(np.array_equal(np.loadtxt(path("mp.txt"), dtype=np.int64), mc), "specseg match on the saved Shape: the CLI's map")
    # landmark-free with the hypothesis options (cheap ones): the CLI's map and its --json numbers
    flags = ["--hypotheses", 2, "--one-way", "--final-zoomout", 0, "--no-polish", "--no-recheck", "--flip-by", "x",
             "--scale-fit", "--zoomout-step", 10, "--skip-tol", 0.05, "--min-coverage", 0.99]
    out = cli("match", path("s.sss"), path("s.sss"), *flags, "--json", "-o", path("mh.txt"))
    jh = json.loads(out)["results"][0]
    rh = specseg.match(S, S, hypotheses=2, one_way=True, final_zoomout=0, polish=False, recheck=False, flip_by="x",
                       scale_fit=True, zoomout_step=10, skip_tol=0.05, min_coverage=0.99)
    check(np.array_equal(np.loadtxt(path("mh.txt"), dtype=np.int64), rh.map), "match with hypothesis options: the CLI's map")
    check(rh.confident == bool(jh["confident"]) and rh.hypothesis == jh["hypothesis"] and
          rh.margin == jh["hypothesis_margin"], "match: confident / hypothesis / margin as --json")
    check(len(rh.hypotheses) == len(jh["hypotheses"]) >= 2, "match: %d hypotheses" % len(rh.hypotheses))
    cov = len(np.unique(rh.map)) / S.n
    check(rh.coverage == jh["coverage"] and abs(rh.coverage - cov) < 1e-12,
          "match: coverage %r as --json %r and as counted %r" % (rh.coverage, jh["coverage"], cov))
    check(rh.coverage >= 0.99 or not rh.confident, "match: below min_coverage 0.99 not confident (%r)" % rh.coverage)
    check((rp.hypothesis is None) == (rp.coverage is None) and (rp.coverage is None or 0 < rp.coverage <= 1),
          "match with landmarks: coverage %r where hypotheses were formed (hypothesis %r)" % (rp.coverage, rp.hypothesis))
    for a, b in zip(rh.hypotheses, jh["hypotheses"]):
        check(all((b[key] is None and math.isnan(a[key])) or a[key] == b[key] for key in b if key not in ("from",)),
              "match: a hypothesis's numbers as --json: %r / %r" % (a, b))
    check(any(h["scale"] != 1.0 for h in rh.hypotheses if "skipped_by" not in h), "match: scale_fit fits a scale")
    try:
        specseg.match(S, S, skip_tol=-1)
        check(False, "match: skip_tol -1 refused")
    except ValueError as ex:
        check("skip_tol" in str(ex), "match: skip_tol -1 refused (%s)" % ex)
    try:
        specseg.match(S, S, min_coverage=1.5)
        check(False, "match: min_coverage 1.5 refused")
    except ValueError as ex:
        check("min_coverage" in str(ex), "match: min_coverage 1.5 refused (%s)" % ex)
    cli("prepare", MESH, "-o", path("c.sss"))
    S3 = specseg.Shape.load(path("c.sss"))
    # (the CLI runs OpenBLAS on one thread: the last bits of the eigenpairs may differ from here)
    check(np.array_equal(S3.labels, S.labels), "Shape.load of specseg prepare: labels")
    check(np.allclose(S3.eigenvalues, Sd.eigenvalues, rtol=1e-9, atol=1e-12),
          "Shape.load of specseg prepare: eigenvalues %s" % np.abs(S3.eigenvalues - Sd.eigenvalues).max())
    S30 = specseg.prepare(V, F, k=30, signature=False)
    try:
        specseg.match(S30, S, lm, k=20)
        check(False, "match: a Shape with too few eigenpairs accepted")
    except specseg.SpecsegError as ex:
        check("prepared with 30 eigenpairs" in str(ex), "too few eigenpairs: %s" % ex)
    with open(path("s.sss"), "r+b") as f:
        f.seek(os.path.getsize(path("s.sss")) // 2)
        f.write(b"\xff\x00")
    try:
        specseg.Shape.load(path("s.sss"))
        check(False, "Shape.load of a damaged file succeeded")
    except specseg.SpecsegError as ex:
        check("damaged prepared shape" in str(ex), "damaged file: %s" % ex)
    try:
        specseg.match(S, (V, F), lm)
        check(False, "match(Shape, arrays) accepted")
    except ValueError:
        check(True, "")

    # --- refine: the CLI's map, from arrays and from Shapes; the identity stays; bad maps refused ---
    ident = np.arange(n)
    rough = ident.copy()
    rough[::3] = np.clip(rough[::3] + 1, 0, n - 1)  # every 3rd vertex to the next index
    np.savetxt(path("rough.txt"), rough, fmt="%d")
    cli("refine", MESH, MESH, path("rough.txt"), "--k", 20, "--zoomout", 40, "-o", path("rf.txt"))
    mr, Cr = specseg.refine(V, F, V, F, rough, k=20, zoomout=40)
    check(np.array_equal(mr, np.loadtxt(path("rf.txt"), dtype=np.int64)), "refine: the CLI's map")
    check(Cr.shape == (40, 40) and np.isfinite(Cr).all(), "refine: C %s" % (Cr.shape,))
    ms, _ = specseg.refine(S, S, rough, k=20, zoomout=40)
    check(np.array_equal(ms, specseg.refine(S, S, map=rough, k=20, zoomout=40)[0]), "refine(Shape, Shape, map=)")
    mi, _ = specseg.refine(S, S, ident, k=20, zoomout=40)
    check(np.array_equal(mi, ident), "refine: the identity onto itself stays")
    for bad in (dict(map=rough[:-1]), dict(map=np.where(ident == 0, n, ident)), dict(map=rough, k=30, zoomout=20),
                dict(map=rough, zoomout_samples=-1)):
        try:
            specseg.refine(S, S, **bad)
            check(False, "refine accepted %r" % sorted(bad))
        except ValueError:
            check(True, "")
    # --- polish: the CLI's map, from arrays and from Shapes; the identity stays; bad maps refused ---
    cli("refine", MESH, MESH, path("rough.txt"), "--polish-only", "-o", path("po.txt"))
    mp = specseg.polish(V, F, V, F, rough)
    check(np.array_equal(mp, np.loadtxt(path("po.txt"), dtype=np.int64)), "polish: the CLI's map")
    check(np.array_equal(specseg.polish(S, S, rough), mp), "polish(Shape, Shape, map)")
    check(np.array_equal(specseg.polish(V, F, V, F, ident), ident), "polish: the identity onto itself stays")
    for bad in (dict(map=rough[:-1]), dict(map=np.where(ident == 0, n, ident))):
        try:
            specseg.polish(S, S, **bad)
            check(False, "polish accepted %r" % sorted(bad))
        except ValueError:
            check(True, "")
    try:
        specseg.refine(S30, S30, rough, k=20, zoomout=40)
        check(False, "refine: a Shape with too few eigenpairs accepted")
    except specseg.SpecsegError as ex:
        check("needs 40" in str(ex), "refine, too few eigenpairs: %s" % ex)

# --- render: background, shape, the labels' colours appear ---
img = specseg.render(V, F, labels=seg.labels, size=(120, 160))
check(img.shape == (160, 120, 3) and img.dtype == np.uint8, "render: shape")
check((img[0, 0] == 255).all(), "render: background corner")
check((img != 255).any(axis=2).mean() > 0.05, "render: the shape covers the image")
# the same picture as the CLI's, pixel for pixel
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png_check import read_png  # noqa: E402
cli("render", MESH, "--labels", path("labels.txt"), "--size", "120x160", "--no-titles", "-o", path("c.png"))
w, h, rows = read_png(path("c.png"))
cimg = np.frombuffer(b"".join(bytes(r) for r in rows), np.uint8).reshape(h, w, 3)
check(cimg.shape == img.shape and np.array_equal(cimg, img), "render: same pixels as specseg render")
# up: a z-up copy ((x, y, z) -> (x, -z, y)) drawn with up="z" or "auto" is the y-up picture
Vz = np.stack([V[:, 0], -V[:, 2], V[:, 1]], 1)
check(np.array_equal(specseg.render(Vz, F, labels=seg.labels, size=(120, 160), up="z"), img), "render: up='z'")
check(np.array_equal(specseg.render(Vz, F, labels=seg.labels, size=(120, 160), up="auto"), img), "render: up='auto'")
check(not np.array_equal(specseg.render(Vz, F, labels=seg.labels, size=(120, 160)), img), "render: default up is y")
try:
    specseg.render(V, F, up="w")
    check(False, "render: up='w' accepted")
except ValueError:
    check(True, "render: up='w' refused")
al = specseg.align_labels((seg.labels + 3) % seg.m, seg.labels)
check(np.array_equal(al, seg.labels), "align_labels undoes a permutation")
specseg.write_png(path("b.png"), img)
with open(path("b.png"), "rb") as f:
    check(f.read(8) == b"\x89PNG\r\n\x1a\n", "write_png signature")

# --- read_mesh of STL (binary) and glTF (our readers, in every build): the vertices welded in order of first
#     occurrence, as float32; the same mesh as the CLI reads (segment --ply writes the input mesh it
#     read, float64) ---
first = np.unique(F.ravel(), return_index=True)
order = first[0][np.argsort(first[1])]            # vertices in order of first occurrence in F
new_id = np.full(n, -1, np.int64)
new_id[order] = np.arange(order.size)
V32 = V.astype(np.float32)
with open(path("m.stl"), "wb") as f:
    f.write(b"binary stl".ljust(80, b" ") + np.uint32(F.shape[0]).tobytes())
    rec = np.zeros(F.shape[0], dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["v"] = V32[F]
    f.write(rec.tobytes())
Vs, Fs = specseg.read_mesh(path("m.stl"))
check(Vs.shape == (order.size, 3) and np.array_equal(Fs, new_id[F]), "read_mesh STL: welded faces")
check(np.array_equal(Vs, V32[order].astype(np.float64)), "read_mesh STL: float32 vertices, first-occurrence order")
cli("segment", path("m.stl"), "-o", path("ls.txt"), "--ply", path("ms.ply"), "--faces", 4000)
Vp, Fp = specseg.read_mesh(path("ms.ply"))
check(np.array_equal(Vp, Vs) and np.array_equal(Fp, Fs), "read_mesh STL = the mesh specseg reads")
blob = V32.tobytes() + F.astype(np.uint32).tobytes()
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "scale": [2, 2, 2]}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
     "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": V32.nbytes},
                     {"buffer": 0, "byteOffset": V32.nbytes, "byteLength": F.size * 4}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
                    "min": V32.min(0).tolist(), "max": V32.max(0).tolist()},
                   {"bufferView": 1, "componentType": 5125, "count": F.size, "type": "SCALAR"}]}
with open(path("m.gltf"), "w") as f:
    json.dump(g, f)
Vg, Fg = specseg.read_mesh(path("m.gltf"))
# an indexed mesh: the weld keeps the first of equal vertices in the file's vertex order
_, first_i, inv = np.unique(V32, axis=0, return_index=True, return_inverse=True)
keep = np.sort(first_i)
gid = np.searchsorted(keep, first_i[inv.ravel()])
check(np.array_equal(Fg, gid[F]) and np.array_equal(Vg, 2 * V32[keep].astype(np.float64)),
      "read_mesh glTF: the node's scale applied, equal vertices welded")

# --- the library's calls run with OpenBLAS single-threaded; the caller's setting comes back ---
from specseg import _clib  # noqa: E402
if _clib._ob_get is not None and not os.environ.get("OPENBLAS_NUM_THREADS"):
    _clib._ob_set(2)
    with _clib.one_blas_thread():
        inside = _clib._ob_get()
        with _clib.one_blas_thread():  # nested
            inside2 = _clib._ob_get()
        after_nested = _clib._ob_get()
    check(inside == 1 and inside2 == 1 and after_nested == 1, "one BLAS thread inside (got %d, %d, %d)"
          % (inside, inside2, after_nested))
    check(_clib._ob_get() == 2, "the caller's 2 BLAS threads restored (got %d)" % _clib._ob_get())
    specseg.eigs(V, F, 6)
    check(_clib._ob_get() == 2, "eigs leaves the caller's BLAS threads (got %d)" % _clib._ob_get())
    try:
        with _clib.one_blas_thread():  # a call that raises restores them too
            raise specseg.SpecsegError("invalid input", "test")
    except specseg.SpecsegError:
        pass
    check(_clib._ob_get() == 2, "a failed call leaves the caller's BLAS threads (got %d)" % _clib._ob_get())
    _clib._ob_set(1)
else:
    print("SKIP: BLAS threads (not OpenBLAS, or OPENBLAS_NUM_THREADS set)")

# --- errors come back as exceptions carrying the library message ---
try:
    specseg.read_mesh(path("missing.off"))
    check(False, "read_mesh of a missing file raises")
except specseg.SpecsegError as ex:
    check("missing.off" in str(ex) and ex.status, "SpecsegError carries the message: %s" % ex)
try:
    specseg.eigs(V, F, n + 5)
    check(False, "eigs with k >= n raises")
except ValueError:
    check(True, "")
try:
    specseg.geodesic(V, F[:, :2], [0])
    check(False, "bad F shape raises")
except ValueError:
    check(True, "")

# issue 32, item 8: max_dist as the CLI's --max-dist (positive; None or inf: no limit); prepare's
# errors say prepare, not match
for bad_md in (-1, 0, float("nan")):
    try:
        specseg.geodesic(V, F, [0], max_dist=bad_md)
        check(False, "geodesic max_dist=%r raises" % bad_md)
    except ValueError as ex:
        check("max_dist" in str(ex), "geodesic max_dist=%r: %s" % (bad_md, ex))
check(np.array_equal(specseg.geodesic(V, F, [0], max_dist=float("inf")), specseg.geodesic(V, F, [0])),
      "geodesic max_dist=inf: no limit")
if specseg._clib.has("ss_prepared_shape_compute"):
    try:
        specseg.prepare(V, F, k=2)
        check(False, "prepare(k=2) raises")
    except (ValueError, specseg.SpecsegError) as ex:
        check(str(ex).startswith("prepare:"), "prepare(k=2): the message names prepare: %s" % ex)

print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
