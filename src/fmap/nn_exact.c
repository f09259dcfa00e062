/* Exact nearest neighbours by cluster pruning.
 *
 * The database is split into ~1.5 √n clusters around farthest-point seeds (in the embedding, so it
 * works for any point set); each cluster keeps its centroid c, its radius R and every member's
 * distance r_b to c. A query q first scans the cluster of its nearest centroid, then skips any
 * cluster with ‖q − c‖ − R above the best distance so far and any point with |‖q − c‖ − r_b| above
 * it (triangle inequality), with bounds widened by the rounding error of the BLAS-computed ‖q − c‖ so
 * that the true neighbour is never pruned. Distances themselves are exact Σ (q_j − b_j)². Spectral
 * embeddings of surfaces are 2-D manifolds in 30–100 dimensions: on FAUST a query evaluates
 * ~100–250 of 6,890 points. */
#include "specseg/fmap.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef NN_CLUSTER_FACTOR
#define NN_CLUSTER_FACTOR 1.5
#endif
static double d2row(int d, const double *a, const double *b) {
  double s = 0;
  /* omp simd: lets the compiler reassociate the sum into vector lanes (no -ffast-math needed) */
#pragma omp simd reduction(+ : s)
  for (int j = 0; j < d; j++) {
    double t = a[j] - b[j];
    s += t * t;
  }
  return s;
}

ss_status ss_nn_exact(int ndb, int nq, int d, const double *db, int lddb, const double *q, int ldq, int *idx,
                      double *dist2, ss_error *err) {
  if (ndb < 1 || nq < 0 || d < 1 || lddb < ndb || ldq < nq)
    return ss_fail(err, SS_ERR_INVALID, "nearest neighbours: bad sizes (ndb %d, nq %d, d %d)", ndb, nq, d);
  if (nq == 0) return SS_OK;
  if (ndb < 256) return ss_nn_brute(ndb, nq, d, db, lddb, q, ldq, idx, dist2, err);
  int nc = (int)(NN_CLUSTER_FACTOR * sqrt((double)ndb));
  double *P = malloc(sizeof(double) * (size_t)ndb * d), *Pc = malloc(sizeof(double) * (size_t)ndb * d);
  double *cen = calloc((size_t)nc * d, sizeof(double));
  double *R = calloc(nc, sizeof(double)), *rp = malloc(sizeof(double) * ndb);
  int *asg = malloc(sizeof(int) * ndb), *start = calloc((size_t)nc + 1, sizeof(int)), *orig = malloc(sizeof(int) * ndb);
  if (!P || !Pc || !cen || !R || !rp || !asg || !start || !orig) {
    free(P); free(Pc); free(cen); free(R); free(rp); free(asg); free(start); free(orig);
    return ss_fail(err, SS_ERR_NOMEM, "nearest neighbours: out of memory");
  }
  /* row-major copy: one point per contiguous row */
  for (int j = 0; j < d; j++)
    for (int b = 0; b < ndb; b++) P[(size_t)b * d + j] = db[b + (size_t)lddb * j];
  { /* farthest-point seeds (better spread than random seeds or Lloyd-refined ones: measured faster
     * searches on FAUST at k = 50..100); every point then joins its nearest seed (one dgemm). Any
     * partition keeps the search exact; compact clusters only make it faster. */
    double *Sd = malloc(sizeof(double) * (size_t)nc * d), *DS = malloc(sizeof(double) * (size_t)ndb * nc);
    double *sn = malloc(sizeof(double) * nc), *mind = malloc(sizeof(double) * ndb);
    if (!Sd || !DS || !sn || !mind) {
      free(Sd); free(DS); free(sn); free(mind);
      free(P); free(Pc); free(cen); free(R); free(rp); free(asg); free(start); free(orig);
      return ss_fail(err, SS_ERR_NOMEM, "nearest neighbours: out of memory");
    }
    for (int b = 0; b < ndb; b++) mind[b] = INFINITY;
    int cur = 0;
    for (int c = 0; c < nc; c++) {
      const double *sp = P + (size_t)cur * d;
      sn[c] = 0;
      for (int j = 0; j < d; j++) {
        Sd[c + (size_t)nc * j] = sp[j];
        sn[c] += sp[j] * sp[j];
      }
      int far = 0;
      double fd = -1;
#pragma omp parallel
      {
        int lf = 0;
        double lfd = -1;
#pragma omp for schedule(static)
        for (int x = 0; x < ndb; x++) {
          double e = d2row(d, sp, P + (size_t)x * d);
          if (e < mind[x]) mind[x] = e;
          if (mind[x] > lfd) { lfd = mind[x]; lf = x; }
        }
#pragma omp critical
        if (lfd > fd || (lfd == fd && lf < far)) { fd = lfd; far = lf; }
      }
      cur = far; /* duplicates (fd = 0) only leave some clusters empty */
    }
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, ndb, nc, d, 1.0, db, lddb, Sd, nc, 0.0, DS, ndb);
#pragma omp parallel for schedule(static)
    for (int b = 0; b < ndb; b++) {
      int bc = 0;
      double bv = INFINITY;
      for (int c = 0; c < nc; c++) {
        double v = sn[c] - 2.0 * DS[b + (size_t)ndb * c];
        if (v < bv) { bv = v; bc = c; }
      }
      asg[b] = bc;
    }
    free(Sd); free(DS); free(sn); free(mind);
  }
  /* bucket by cluster, centroids, radii */
  for (int b = 0; b < ndb; b++) start[asg[b] + 1]++;
  for (int c = 0; c < nc; c++) start[c + 1] += start[c];
  {
    int *fill = malloc(sizeof(int) * nc);
    if (!fill) {
      free(P); free(Pc); free(cen); free(R); free(rp); free(asg); free(start); free(orig);
      return ss_fail(err, SS_ERR_NOMEM, "nearest neighbours: out of memory");
    }
    memcpy(fill, start, sizeof(int) * nc);
    for (int b = 0; b < ndb; b++) { /* ascending b within each cluster: ties resolve to the lower index */
      int slot = fill[asg[b]]++;
      orig[slot] = b;
      memcpy(Pc + (size_t)slot * d, P + (size_t)b * d, sizeof(double) * d);
    }
    free(fill);
  }
  for (int c = 0; c < nc; c++) {
    double *cc = cen + (size_t)c * d;
    int cnt = start[c + 1] - start[c];
    for (int s = start[c]; s < start[c + 1]; s++)
      for (int j = 0; j < d; j++) cc[j] += Pc[(size_t)s * d + j];
    for (int j = 0; j < d; j++) cc[j] /= cnt > 0 ? cnt : 1;
    for (int s = start[c]; s < start[c + 1]; s++) {
      rp[s] = sqrt(d2row(d, cc, Pc + (size_t)s * d));
      R[c] = fmax(R[c], rp[s]);
    }
  }
  /* query-centre squared distances by one dgemm; rounding is absorbed into lower/upper bounds */
  double *DQ = malloc(sizeof(double) * (size_t)nq * nc), *cn = malloc(sizeof(double) * nc);
  double *qn = malloc(sizeof(double) * nq);
  int fail = !DQ || !cn || !qn;
  if (!fail) {
    for (int c = 0; c < nc; c++) {
      double t = 0;
      for (int j = 0; j < d; j++) t += cen[(size_t)c * d + j] * cen[(size_t)c * d + j];
      cn[c] = t;
    }
    for (int i = 0; i < nq; i++) qn[i] = 0;
    for (int j = 0; j < d; j++)
      for (int i = 0; i < nq; i++) qn[i] += q[i + (size_t)ldq * j] * q[i + (size_t)ldq * j];
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, nq, nc, d, 1.0, q, ldq, cen, d, 0.0, DQ, nq);
  }
#pragma omp parallel if (!fail)
  {
    double *qr = malloc(sizeof(double) * d), *dlo = malloc(sizeof(double) * nc), *dhi = malloc(sizeof(double) * nc);
    if (fail || !qr || !dlo || !dhi) {
#pragma omp atomic write
      fail = 1;
    } else {
#pragma omp for schedule(dynamic, 32)
      for (int i = 0; i < nq; i++) {
        for (int j = 0; j < d; j++) qr[j] = q[i + (size_t)ldq * j];
        int c0 = 0;
        double b0 = INFINITY;
        for (int c = 0; c < nc; c++) {
          double v = qn[i] - 2.0 * DQ[i + (size_t)nq * c] + cn[c], tol = 1e-12 * (d + 8) * (qn[i] + cn[c]);
          dlo[c] = sqrt(fmax(0.0, v - tol));
          dhi[c] = sqrt(fmax(0.0, v + tol));
          if (v < b0) { b0 = v; c0 = c; }
        }
        double best = INFINITY;
        int bi = -1;
        /* the closest centre's cluster first (a tight bound at once), then every cluster the bound
         * cannot exclude; inside a cluster, |‖q − c‖ − ‖b − c‖| ≤ ‖q − b‖ skips most points */
        for (int t = -1; t < nc; t++) {
          int c = t < 0 ? c0 : t;
          if (t == c0) continue;
          double rb = sqrt(best), margin = 1e-9 * (dhi[c] + R[c] + rb);
          if (dlo[c] - R[c] > rb + margin) continue;
          for (int s = start[c]; s < start[c + 1]; s++) {
            if (dlo[c] - rp[s] > rb + margin || rp[s] - dhi[c] > rb + margin) continue;
            double e = d2row(d, qr, Pc + (size_t)s * d);
            if (e < best || (e == best && orig[s] < bi)) {
              best = e;
              bi = orig[s];
              rb = sqrt(best);
              margin = 1e-9 * (dhi[c] + R[c] + rb);
            }
          }
        }
        if (bi < 0) { /* NaN coordinates: no finite distance, fall back to the first point */
          bi = 0;
          best = d2row(d, qr, P);
        }
        idx[i] = bi;
        if (dist2) dist2[i] = best;
      }
    }
    free(qr);
    free(dlo);
    free(dhi);
  }
  free(DQ);
  free(cn);
  free(qn);
  free(P); free(Pc); free(cen); free(R); free(rp); free(asg); free(start); free(orig);
  if (fail) return ss_fail(err, SS_ERR_NOMEM, "nearest neighbours: out of memory");
  return SS_OK;
}
