#!/usr/bin/env python3
"""Reference timing for bench_eigs: scipy.sparse.linalg.eigsh(W, k, M=M, sigma=-1e-8) on the very
matrices specseg exported (PREFIX_I.npy, PREFIX_J.npy, PREFIX_X.npy: triplets of W; PREFIX_M.npy:
lumped masses). Prints "scipy_seconds T" (wall) and "scipy_cpu_seconds C" (this process's CPU time,
all threads) for each repetition and writes the eigenvalues to
PREFIX_scipy_evals.npy so the caller can compare them with its own."""
import sys
import time

import numpy as np
import scipy
import scipy.sparse as sp
import scipy.sparse.linalg as sla


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: bench_eigs_scipy.py PREFIX K [REPEATS] [SIGMA]")
    prefix, k = sys.argv[1], int(sys.argv[2])
    reps = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    sigma = float(sys.argv[4]) if len(sys.argv) > 4 else -1e-8
    I = np.load(prefix + "_I.npy").ravel().astype(np.int64)
    J = np.load(prefix + "_J.npy").ravel().astype(np.int64)
    X = np.load(prefix + "_X.npy").ravel()
    m = np.load(prefix + "_M.npy").ravel()
    n = m.size
    W = sp.csc_matrix((X, (I, J)), shape=(n, n))
    M = sp.diags(m).tocsc()
    print(f"scipy {scipy.__version__}, n={n}, nnz(W)={W.nnz}, k={k}", flush=True)
    for _ in range(reps):
        t0 = time.perf_counter()
        c0 = time.process_time()
        vals, vecs = sla.eigsh(W, k=k, M=M, sigma=sigma)
        t = time.perf_counter() - t0
        c = time.process_time() - c0
        print(f"scipy_seconds {t:.6f}", flush=True)
        print(f"scipy_cpu_seconds {c:.6f}", flush=True)
    order = np.argsort(vals)
    vals, vecs = vals[order], vecs[:, order]
    R = W @ vecs - (M @ vecs) * vals
    rel = np.linalg.norm(R, axis=0) / ((np.abs(vals) + 1) * np.linalg.norm(M @ vecs, axis=0))
    G = vecs.T @ (M @ vecs)
    print(f"scipy_max_rel_residual {rel.max():.3e}", flush=True)
    print(f"scipy_max_orth_error {np.abs(G - np.eye(k)).max():.3e}", flush=True)
    np.save(prefix + "_scipy_evals.npy", vals)


if __name__ == "__main__":
    main()
