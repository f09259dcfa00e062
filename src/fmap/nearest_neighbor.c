/* Exact nearest neighbours by cluster pruning.
 *
 * The database is split into ~1.5 √n clusters around farthest-point seeds (in the embedding, so it
 * works for any point set); each cluster keeps its centroid c, its radius R and a local frame (see
 * nn_index). A query q first scans the cluster of its nearest centroid, then every cluster with
 * ‖q − c‖ − R not above the best distance so far; inside a cluster the frame bound skips most
 * points. Bounds are widened by their rounding errors so that the true neighbour is never pruned;
 * distances themselves are exact Σ (q_j − b_j)². Spectral embeddings of surfaces are 2-D manifolds
 * in 30–100 dimensions: on FAUST a query opens ~5–10 of 124 clusters and evaluates ~5–15 of 6,890
 * points.
 *
 * ss_nn_exact_guided serves ZoomOut, which searches once per iteration: a guess per query (the
 * previous iteration's match) bounds the search before the first cluster, and the partition is
 * given (one for all iterations) instead of re-seeded, which was a quarter of the cost. Any partition
 * keeps the search exact; compact ones make it fast. */
#include "specseg/fmap.h"
#include "util/asan_region.h"

#include <cblas.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef NN_CLUSTER_FACTOR
#define NN_CLUSTER_FACTOR 1.5
#endif
/* Σ (a_j − b_j)², its ranges checked by the caller (scan_cluster checks the query once, each row it reads) */
SSI_RANGE_CHECKED static inline double d2sum(int d, const double *a, const double *b) {
  double s = 0;
  /* omp simd: lets the compiler reassociate the sum into vector lanes (no -ffast-math needed) */
#pragma omp simd reduction(+ : s)
  for (int j = 0; j < d; j++) {
    double t = a[j] - b[j];
    s += t * t;
  }
  return s;
}

SSI_RANGE_CHECKED static double d2row(int d, const double *a, const double *b) {
  ssi_checked_doubles(a, d), ssi_checked_doubles(b, d);
  return d2sum(d, a, b);
}

static int default_clusters(int n) { return (int)(NN_CLUSTER_FACTOR * sqrt((double)n)); }

/* Doubles of query-centre (and point-seed) distance table per block: the tables are n x nc with
 * nc ~ 1.5 √n, ~12 GB each at 10^6 points in one piece; in blocks of ~64 MB a FAUST-sized search is
 * still one block. */
#define NN_TABLE_DOUBLES (8u << 20)

static int block_rows(int nc) {
  size_t r = NN_TABLE_DOUBLES / (size_t)(nc > 0 ? nc : 1);
  return r < 1024 ? 1024 : r > (size_t)INT_MAX ? INT_MAX : (int)r;
}

/* mind[x] = min(mind[x], ‖P_x − sp‖²) for the n rows of P; returns the row farthest from every seed so
 * far (the first of equals). Serial: a parallel loop per seed meant ~120 barriers per call, each
 * costing a time slice whenever the machine is shared (ZoomOut took up to 70 s instead of 3). */
SSI_RANGE_CHECKED static int nearest_seed_update(int n, int d, const double *sp, const double *P, double *mind) {
  ssi_checked_doubles(sp, d), ssi_checked_doubles(P, (size_t)n * d), ssi_checked_doubles(mind, n);
  int far = 0;
  double fd = -1;
  for (int x = 0; x < n; x++) {
    double e = d2sum(d, sp, P + (size_t)x * d);
    if (e < mind[x]) mind[x] = e;
    if (mind[x] > fd) { fd = mind[x]; far = x; }
  }
  return far;
}

/* Farthest-point seeds (better spread than random seeds or Lloyd-refined ones: measured faster
 * searches on FAUST at k = 50..100); every point then joins its nearest seed (one dgemm). Any
 * partition keeps the search exact; compact clusters only make it faster. P: row-major copy of X. */
static int fps_partition(int n, int d, int nc, const double *P, const double *X, int ldx, int *asg) {
  const int rb = block_rows(nc) < n ? block_rows(nc) : n; /* point rows per block of the seed table */
  double *Sd = malloc(sizeof(double) * (size_t)nc * d), *DS = malloc(sizeof(double) * (size_t)rb * nc);
  double *sn = malloc(sizeof(double) * nc), *mind = malloc(sizeof(double) * n);
  if (!Sd || !DS || !sn || !mind) {
    free(Sd); free(DS); free(sn); free(mind);
    return 1;
  }
  for (int b = 0; b < n; b++) mind[b] = INFINITY;
  int cur = 0;
  for (int c = 0; c < nc; c++) {
    const double *sp = P + (size_t)cur * d;
    sn[c] = 0;
    for (int j = 0; j < d; j++) {
      Sd[c + (size_t)nc * j] = sp[j];
      sn[c] += sp[j] * sp[j];
    }
    cur = nearest_seed_update(n, d, sp, P, mind); /* duplicates (distance 0) only leave some clusters empty */
  }
  for (int b0 = 0; b0 < n; b0 += rb) {
    const int m = n - b0 < rb ? n - b0 : rb;
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, m, nc, d, 1.0, X + b0, ldx, Sd, nc, 0.0, DS, m);
#pragma omp parallel for schedule(static)
    for (int b = 0; b < m; b++) {
      int bc = 0;
      double bv = INFINITY;
      for (int c = 0; c < nc; c++) {
        double v = sn[c] - 2.0 * DS[b + (size_t)m * c];
        if (v < bv) { bv = v; bc = c; }
      }
      asg[b0 + b] = bc;
    }
  }
  free(Sd); free(DS); free(sn); free(mind);
  return 0;
}

ss_status ss_nn_partition(int n, int d, const double *X, int ldx, int nc, int *part, ss_error *err) {
  if (n < 1 || d < 1 || ldx < n) return ss_fail(err, SS_ERR_INVALID, "nn partition: bad sizes (n %d, d %d)", n, d);
  if (!X || !part) return ss_fail(err, SS_ERR_INVALID, "nn partition: NULL points or output");
  if (nc <= 0) nc = default_clusters(n);
  if (nc < 1) nc = 1;
  if (nc > n) nc = n;
  double *P = malloc(sizeof(double) * (size_t)n * d);
  if (!P) return ss_fail(err, SS_ERR_NOMEM, "nn partition: out of memory");
  for (int j = 0; j < d; j++)
    for (int b = 0; b < n; b++) P[(size_t)b * d + j] = X[b + (size_t)ldx * j];
  int bad = fps_partition(n, d, nc, P, X, ldx, part);
  free(P);
  return bad ? ss_fail(err, SS_ERR_NOMEM, "nn partition: out of memory") : SS_OK;
}

/* The database bucketed by cluster: rows of Pc (row-major, cluster by cluster, ascending original
 * index inside a cluster so that ties resolve to the lower index), centroids c, radii R, and a local
 * frame per cluster: NN_FRAME orthonormal directions U (pivoted Gram–Schmidt of the centred members,
 * close to their principal plane: the embedding is a 2-D surface) with every member's coordinates
 * y_b = Uᵀ(b − c) and off-frame residual h_b = ‖(b − c) − U y_b‖. For any q, with z = Uᵀ(q − c) and
 * h_q = ‖(q − c) − U z‖, ‖q − b‖² ≥ ‖z − y_b‖² + (h_q − h_b)² (Pythagoras, then the triangle
 * inequality off the frame). It implies |‖q − c‖ − ‖b − c‖| ≤ ‖q − b‖ and is far tighter: on FAUST
 * at k = 50..100 it leaves ~5–10 exact distances per query instead of ~100. */
#ifndef NN_FRAME
#define NN_FRAME 3 /* FAUST: 2 → ~12 exact distances per query, 3 → ~8, 4 → ~5; 2 and 3 equally fast, 4 slower */
#endif
#if NN_FRAME < 1 || NN_FRAME > 4
#error "NN_FRAME must be 1..4"
#endif
typedef struct nn_index {
  int nc, d, maxcnt;
  int *start, *orig, *slot; /* start[nc+1]; orig[s] = database index of row s; slot = its inverse */
  double *Pc, *cen, *R;
  double *U, *Y, *H;        /* U: nc blocks of NN_FRAME rows of d; Y: NN_FRAME arrays of ndb; H: ndb */
} nn_index;

static void index_free(nn_index *t) {
  free(t->start); free(t->orig); free(t->slot);
  free(t->Pc); free(t->cen); free(t->R);
  free(t->U); free(t->Y); free(t->H);
}

SSI_RANGE_CHECKED static double dot(int d, const double *a, const double *b) {
  ssi_checked_doubles(a, d), ssi_checked_doubles(b, d);
  double s = 0;
#pragma omp simd reduction(+ : s)
  for (int j = 0; j < d; j++) s += a[j] * b[j];
  return s;
}

/* Centroid, radius and frame of cluster c; W: scratch of maxcnt x d, nrm: of maxcnt. The frame's
 * pivots are chosen on squared norms updated by −p² (a choice only: the pivot's own residual is then
 * taken exactly); coordinates and off-frame residuals are computed from scratch, one fused pass each. */
SSI_RANGE_CHECKED static void cluster_setup(nn_index *t, int ndb, int c, double *W, double *nrm) {
  ssi_checked_object(t), ssi_checked_ints(t->start + c, 2), ssi_checked_doubles(t->R + c, 1);
  const int d = t->d, s0 = t->start[c], cnt = t->start[c + 1] - s0;
  double *cc = t->cen + (size_t)c * d, *U = t->U + (size_t)c * NN_FRAME * d, R2 = 0;
  ssi_checked_doubles(cc, d), ssi_checked_doubles(U, (size_t)NN_FRAME * d);
  ssi_checked_doubles(t->Pc + (size_t)s0 * d, (size_t)cnt * d), ssi_checked_doubles(W, (size_t)cnt * d);
  ssi_checked_doubles(nrm, cnt), ssi_checked_doubles(t->H + s0, cnt);
  for (int a = 0; a < NN_FRAME; a++) ssi_checked_doubles(t->Y + (size_t)a * ndb + s0, cnt);
  for (int j = 0; j < d; j++) cc[j] = 0;
  for (int s = 0; s < cnt; s++) {
    const double *b = t->Pc + (size_t)(s0 + s) * d;
#pragma omp simd
    for (int j = 0; j < d; j++) cc[j] += b[j];
  }
  for (int j = 0; j < d; j++) cc[j] /= cnt > 0 ? cnt : 1;
  for (int s = 0; s < cnt; s++) { /* centred members and their squared norms (the radius) */
    const double *b = t->Pc + (size_t)(s0 + s) * d;
    double *w = W + (size_t)s * d, q = 0;
#pragma omp simd reduction(+ : q)
    for (int j = 0; j < d; j++) {
      double v = b[j] - cc[j];
      w[j] = v;
      q += v * v;
    }
    nrm[s] = q;
    R2 = fmax(R2, q);
  }
  const double R = sqrt(R2);
  t->R[c] = R;
  for (int a = 0; a < NN_FRAME; a++) { /* next direction: the member farthest from the span so far */
    double *u = U + (size_t)a * d, bn = 0;
    int bs = -1;
    for (int s = 0; s < cnt; s++)
      if (nrm[s] > bn) { bn = nrm[s]; bs = s; }
    for (int j = 0; j < d; j++) u[j] = bs < 0 ? 0 : W[(size_t)bs * d + j];
    bn = dot(d, u, u); /* the pivot's residual, exactly */
    for (int pass = 0; pass < 2; pass++) /* re-orthogonalised */
      for (int a2 = 0; a2 < a; a2++) {
        const double *v = U + (size_t)a2 * d;
        double p = dot(d, u, v);
        for (int j = 0; j < d; j++) u[j] -= p * v[j];
      }
    /* a residual at rounding level (the members span fewer than NN_FRAME directions) would normalise
     * to a vector far from orthogonal to the others: such directions stay zero */
    double nu = sqrt(dot(d, u, u));
    int keep = sqrt(bn) > 1e-9 * R && nu > 0.5 * sqrt(bn);
    for (int j = 0; j < d; j++) u[j] = keep ? u[j] / nu : 0;
    for (int s = 0; s < cnt && keep && a + 1 < NN_FRAME; s++) { /* (the last direction needs no update) */
      double *w = W + (size_t)s * d, p = dot(d, w, u);
#pragma omp simd
      for (int j = 0; j < d; j++) w[j] -= p * u[j];
      nrm[s] -= p * p;
    }
  }
  double dev = 0; /* the bound needs ‖Uᵀx‖ ≤ ‖x‖: check orthonormality, else no frame at all */
  for (int a = 0; a < NN_FRAME; a++)
    for (int a2 = 0; a2 <= a; a2++) {
      double p = dot(d, U + (size_t)a * d, U + (size_t)a2 * d), n2 = dot(d, U + (size_t)a * d, U + (size_t)a * d);
      dev = fmax(dev, fabs(p - (a == a2 ? n2 : 0))); /* zero rows are fine */
      if (a == a2 && n2 != 0) dev = fmax(dev, fabs(n2 - 1));
    }
  if (!(dev < 2e-14)) /* a frame error δ moves h_q by ~√(3δ)‖q − c‖; fm below covers δ = 2e-14 ~4x */
    for (size_t j = 0; j < (size_t)NN_FRAME * d; j++) U[j] = 0;
  /* rows of the frame (absent ones: a zero row, never used with a non-zero weight) */
  const double *U0 = U, *U1 = NN_FRAME > 1 ? U + d : U, *U2 = NN_FRAME > 2 ? U + 2 * (size_t)d : U,
               *U3 = NN_FRAME > 3 ? U + 3 * (size_t)d : U;
  for (int s = 0; s < cnt; s++) { /* coordinates and residuals from scratch, not from the updates */
    const double *b = t->Pc + (size_t)(s0 + s) * d;
    double y0 = 0, y1 = 0, y2 = 0, y3 = 0, h = 0;
#pragma omp simd reduction(+ : y0, y1, y2, y3)
    for (int j = 0; j < d; j++) {
      double v = b[j] - cc[j];
      y0 += v * U0[j];
      y1 += v * U1[j];
      y2 += v * U2[j];
      y3 += v * U3[j];
    }
    if (NN_FRAME < 2) y1 = 0;
    if (NN_FRAME < 3) y2 = 0;
    if (NN_FRAME < 4) y3 = 0;
#pragma omp simd reduction(+ : h)
    for (int j = 0; j < d; j++) {
      double v = b[j] - cc[j] - y0 * U0[j] - y1 * U1[j] - y2 * U2[j] - y3 * U3[j];
      h += v * v;
    }
    const double y[4] = {y0, y1, y2, y3};
    for (int a = 0; a < NN_FRAME; a++) t->Y[(size_t)a * ndb + s0 + s] = y[a];
    t->H[s0 + s] = sqrt(h);
  }
}

/* Pc's row slot[b] = point b of db (column-major, leading dimension lddb): a row-major copy, 16 points
 * at a time (the 16 destination rows stay in cache across the columns) */
SSI_RANGE_CHECKED static void rows_by_slot(int ndb, int d, const double *db, int lddb, const int *slot, double *Pc) {
  ssi_checked_doubles(db, (size_t)lddb * (d - 1) + ndb), ssi_checked_ints(slot, ndb);
  ssi_checked_doubles(Pc, (size_t)ndb * d);
  for (int b0 = 0; b0 < ndb; b0 += 16) {
    const int b1 = b0 + 16 < ndb ? b0 + 16 : ndb;
    for (int j = 0; j < d; j++)
      for (int b = b0; b < b1; b++) Pc[(size_t)slot[b] * d + j] = db[b + (size_t)lddb * j];
  }
}

static int index_build(int ndb, int d, const double *db, int lddb, int nc, const int *asg, nn_index *t) {
  memset(t, 0, sizeof *t);
  t->nc = nc;
  t->d = d;
  t->start = calloc((size_t)nc + 1, sizeof(int));
  t->orig = malloc(sizeof(int) * ndb);
  t->slot = malloc(sizeof(int) * ndb);
  t->Pc = malloc(sizeof(double) * (size_t)ndb * d);
  t->cen = malloc(sizeof(double) * (size_t)nc * d);
  t->R = malloc(sizeof(double) * nc);
  t->U = malloc(sizeof(double) * (size_t)nc * NN_FRAME * d);
  t->Y = malloc(sizeof(double) * (size_t)ndb * NN_FRAME);
  t->H = malloc(sizeof(double) * ndb);
  int *fill = malloc(sizeof(int) * nc);
  if (!t->start || !t->orig || !t->slot || !t->Pc || !t->cen || !t->R || !t->U || !t->Y || !t->H || !fill) {
    free(fill);
    index_free(t);
    return 1;
  }
  for (int b = 0; b < ndb; b++) t->start[asg[b] + 1]++;
  for (int c = 0; c < nc; c++) {
    if (t->start[c + 1] > t->maxcnt) t->maxcnt = t->start[c + 1];
    t->start[c + 1] += t->start[c];
  }
  memcpy(fill, t->start, sizeof(int) * nc);
  for (int b = 0; b < ndb; b++) {
    int s = fill[asg[b]]++;
    t->orig[s] = b;
    t->slot[b] = s;
  }
  free(fill);
  rows_by_slot(ndb, d, db, lddb, t->slot, t->Pc);
  int fail = 0;
#pragma omp parallel
  {
    const size_t mc = (size_t)(t->maxcnt > 0 ? t->maxcnt : 1);
    double *W = malloc(sizeof(double) * mc * d), *nrm = malloc(sizeof(double) * mc);
    if (!W || !nrm) {
#pragma omp atomic write
      fail = 1;
    }
#pragma omp for schedule(dynamic, 4) nowait /* the region's end is the barrier */
    for (int c = 0; c < nc; c++)
      if (W && nrm) cluster_setup(t, ndb, c, W, nrm);
    free(W);
    free(nrm);
  }
  if (fail) index_free(t);
  return fail;
}

/* Per-thread scratch of the search. */
typedef struct nn_scratch {
  double *qr, *lo2, *L2;
  int *list;
} nn_scratch;

/* Scan cluster c for query qr: the exact ‖q − c‖ and frame coordinates in one pass, then the frame
 * bound for every member, then exact distances for the members it cannot exclude. *best, *bi: the
 * running minimum (ties: lower index). NaN bounds never exclude. */
SSI_RANGE_CHECKED static void scan_cluster(const nn_index *t, int ndb, int c, nn_scratch *w, double *best,
                                            int *bi) {
  ssi_checked_object(t), ssi_checked_object(w), ssi_checked_doubles(best, 1), ssi_checked_ints(bi, 1);
  ssi_checked_ints(t->start + c, 2);
  const int d = t->d, s0 = t->start[c], cnt = t->start[c + 1] - s0;
  if (cnt == 0) return;
  const double *qr = w->qr, *cc = t->cen + (size_t)c * d, *U = t->U + (size_t)c * NN_FRAME * d;
  ssi_checked_doubles(qr, d), ssi_checked_doubles(cc, d), ssi_checked_doubles(U, (size_t)NN_FRAME * d);
  ssi_checked_doubles(t->R + c, 1), ssi_checked_doubles(t->H + s0, cnt), ssi_checked_doubles(w->L2, cnt);
  ssi_checked_ints(t->orig + s0, cnt);
  for (int a = 0; a < NN_FRAME; a++) ssi_checked_doubles(t->Y + (size_t)a * ndb + s0, cnt);
  double s2 = 0, z[NN_FRAME];
  {
    double z0 = 0, z1 = 0, z2 = 0, z3 = 0;
    const double *U0 = U, *U1 = U + (NN_FRAME > 1) * d, *U2 = U + 2 * (NN_FRAME > 2) * d, *U3 = U + 3 * (NN_FRAME > 3) * d;
#pragma omp simd reduction(+ : s2, z0, z1, z2, z3)
    for (int j = 0; j < d; j++) {
      double wj = qr[j] - cc[j];
      s2 += wj * wj;
      z0 += wj * U0[j];
      z1 += wj * U1[j];
      z2 += wj * U2[j];
      z3 += wj * U3[j];
    }
    double zz[4] = {z0, z1, z2, z3};
    for (int a = 0; a < NN_FRAME; a++) z[a] = zz[a];
  }
  double rb = sqrt(*best), dq = sqrt(s2), margin = 1e-9 * (dq + t->R[c] + rb);
  if (dq - t->R[c] > rb + margin) return;
  double h2 = s2;
  for (int a = 0; a < NN_FRAME; a++) h2 -= z[a] * z[a];
  /* h2 loses digits to cancellation: its error, ≤ ~7 d ε ‖q − c‖², moves h_q by up to √(7 d ε) ‖q − c‖
   * (2.8e-7 ‖q − c‖ at d = 100); fm is ~8x that */
  double hq = sqrt(h2 > 0 ? h2 : 0), fm = sqrt(1e-13 * (d + 8)) * dq, lim = rb + margin + fm, lim2 = lim * lim;
  const double *H = t->H + s0, *Y0 = t->Y + s0, *Y1 = Y0 + (NN_FRAME > 1) * ndb, *Y2 = Y0 + 2 * (NN_FRAME > 2) * ndb,
               *Y3 = Y0 + 3 * (NN_FRAME > 3) * ndb;
  double *L2 = w->L2, z0 = z[0], z1 = NN_FRAME > 1 ? z[1] : 0, z2 = NN_FRAME > 2 ? z[2] : 0, z3 = NN_FRAME > 3 ? z[3] : 0;
#pragma omp simd
  for (int s = 0; s < cnt; s++) {
    double l = (hq - H[s]) * (hq - H[s]) + (z0 - Y0[s]) * (z0 - Y0[s]);
    if (NN_FRAME > 1) l += (z1 - Y1[s]) * (z1 - Y1[s]);
    if (NN_FRAME > 2) l += (z2 - Y2[s]) * (z2 - Y2[s]);
    if (NN_FRAME > 3) l += (z3 - Y3[s]) * (z3 - Y3[s]);
    L2[s] = l;
  }
  for (int s = 0; s < cnt; s++) {
    if (L2[s] > lim2) continue; /* NaN: never excluded */
    const double *row = t->Pc + (size_t)(s0 + s) * d; /* (only the rows the bound keeps are read) */
    ssi_checked_doubles(row, d);
    double e = d2sum(d, qr, row);
    int o = t->orig[s0 + s];
    if (e < *best || (e == *best && o < *bi)) {
      *best = e;
      *bi = o;
      rb = sqrt(e);
      lim = rb + 1e-9 * (dq + t->R[c] + rb) + fm;
      lim2 = lim * lim;
    }
  }
}

/* One query's lower bounds lo2 on its squared distance to each cluster (Di: the query-centre dgemm
 * column, qi its norm², cn the centres', tq their rounding); returns the cluster of the least bound */
SSI_RANGE_CHECKED static int query_bounds(int nc, const double *Di, double qi, const double *cn, double tq,
                                          double *lo2) {
  ssi_checked_doubles(Di, nc), ssi_checked_doubles(cn, nc), ssi_checked_doubles(lo2, nc);
  for (int c = 0; c < nc; c++) lo2[c] = (qi - 2.0 * Di[c] + cn[c]) - tq * (qi + cn[c]);
  int c0 = 0;
  for (int c = 1; c < nc; c++)
    if (lo2[c] < lo2[c0]) c0 = c;
  return c0;
}

/* The clusters other than c0 that the bound cannot exclude (‖q − c‖ > rb + R, tested on squares),
 * in list; returns how many */
SSI_RANGE_CHECKED static int clusters_to_open(int nc, double rb, const double *R, const double *lo2, int c0,
                                              int *list) {
  ssi_checked_doubles(R, nc), ssi_checked_doubles(lo2, nc), ssi_checked_ints(list, nc);
  int n = 0;
  for (int c = 0; c < nc; c++) {
    double thr = (rb + R[c]) * (1 + 1e-9);
    list[n] = c;
    n += !(lo2[c] > thr * thr) && c != c0;
  }
  return n;
}

/* The search: query-centre squared distances by one dgemm (rounding absorbed into a lower bound)
 * decide which clusters to open; the first bound is the guess's distance (if any), then the closest
 * centre's cluster is scanned first. Returns 1 when out of memory. */
static int search_block(const nn_index *t, int ndb, int nq, const double *q, int ldq, const int *guess, int *idx,
                        double *dist2) {
  int nc = t->nc, d = t->d;
  double *DQ = malloc(sizeof(double) * (size_t)nq * nc), *cn = malloc(sizeof(double) * nc);
  double *qn = malloc(sizeof(double) * nq);
  int fail = !DQ || !cn || !qn;
  if (!fail) {
    for (int c = 0; c < nc; c++) cn[c] = dot(d, t->cen + (size_t)c * d, t->cen + (size_t)c * d);
    for (int i = 0; i < nq; i++) qn[i] = 0;
    for (int j = 0; j < d; j++)
      for (int i = 0; i < nq; i++) qn[i] += q[i + (size_t)ldq * j] * q[i + (size_t)ldq * j];
    /* DQ (nc x nq): one contiguous column per query */
    cblas_dgemm(CblasColMajor, CblasTrans, CblasTrans, nc, nq, d, 1.0, t->cen, d, q, ldq, 0.0, DQ, nc);
  }
  const int go = !fail; /* every thread meets every worksharing loop; a thread without scratch skips */
#pragma omp parallel if (go)
  {
    nn_scratch w;
    w.qr = malloc(sizeof(double) * d);
    w.lo2 = malloc(sizeof(double) * nc);
    w.L2 = malloc(sizeof(double) * (t->maxcnt > 0 ? t->maxcnt : 1));
    w.list = malloc(sizeof(int) * nc);
    int ok = go && w.qr && w.lo2 && w.L2 && w.list;
    if (!ok) {
#pragma omp atomic write
      fail = 1;
    }
    const double tq = 1e-12 * (d + 8);
    if (go) {
#pragma omp for schedule(dynamic, 32) nowait /* the region's end is the barrier */
      for (int i = 0; i < nq; i++) {
        if (!ok) continue;
        for (int j = 0; j < d; j++) w.qr[j] = q[i + (size_t)ldq * j];
        const int c0 = query_bounds(nc, DQ + (size_t)nc * i, qn[i], cn, tq, w.lo2);
        double best = INFINITY;
        int bi = -1;
        if (guess) {
          bi = guess[i];
          best = d2row(d, w.qr, t->Pc + (size_t)t->slot[bi] * d);
          if (!(best < INFINITY)) { best = INFINITY; bi = -1; } /* as unguided: no infinite or NaN match */
        }
        scan_cluster(t, ndb, c0, &w, &best, &bi);
        const double *lo2 = w.lo2;
        const int n = clusters_to_open(nc, sqrt(best), t->R, lo2, c0, w.list);
        for (int k = 0; k < n; k++) {
          int c = w.list[k];
          double thr = (sqrt(best) + t->R[c]) * (1 + 1e-9);
          if (lo2[c] > thr * thr) continue;
          scan_cluster(t, ndb, c, &w, &best, &bi);
        }
        if (bi < 0) { /* NaN coordinates: no finite distance, fall back to the first point */
          bi = 0;
          best = d2row(d, w.qr, t->Pc + (size_t)t->slot[0] * d);
        }
        idx[i] = bi;
        if (dist2) dist2[i] = best;
      }
    }
    free(w.qr); free(w.lo2); free(w.L2); free(w.list);
  }
  free(DQ);
  free(cn);
  free(qn);
  return fail;
}

/* The search in blocks of queries (q is column-major with leading dimension ldq, so a block of rows
 * is q + i0); results do not depend on the blocking. */
static int search(const nn_index *t, int ndb, int nq, const double *q, int ldq, const int *guess, int *idx,
                  double *dist2) {
  const int qb = block_rows(t->nc);
  for (int i0 = 0; i0 < nq; i0 += qb) {
    int m = nq - i0 < qb ? nq - i0 : qb;
    if (search_block(t, ndb, m, q + i0, ldq, guess ? guess + i0 : NULL, idx + i0, dist2 ? dist2 + i0 : NULL)) return 1;
  }
  return 0;
}

ss_status ss_nn_exact_guided(int ndb, int nq, int d, const double *db, int lddb, const double *q, int ldq,
                             const int *part, const int *guess, int *idx, double *dist2, ss_error *err) {
  if (ndb < 1 || nq < 0 || d < 1 || lddb < ndb || ldq < nq)
    return ss_fail(err, SS_ERR_INVALID, "nearest neighbours: bad sizes (ndb %d, nq %d, d %d)", ndb, nq, d);
  if (nq > 0 && (!db || !q || !idx)) return ss_fail(err, SS_ERR_INVALID, "nearest neighbours: NULL points or output");
  if (guess)
    for (int i = 0; i < nq; i++)
      if (guess[i] < 0 || guess[i] >= ndb)
        return ss_fail(err, SS_ERR_INVALID, "nearest neighbours: guess %d = %d out of range [0,%d)", i, guess[i], ndb);
  int nc = default_clusters(ndb);
  if (part) {
    nc = 0;
    for (int b = 0; b < ndb; b++) {
      if (part[b] < 0 || part[b] >= ndb)
        return ss_fail(err, SS_ERR_INVALID, "nearest neighbours: cluster label %d = %d out of range [0,%d)", b,
                       part[b], ndb);
      if (part[b] >= nc) nc = part[b] + 1;
    }
  }
  if (nq == 0) return SS_OK;
  if (ndb < 256) return ss_nn_brute(ndb, nq, d, db, lddb, q, ldq, idx, dist2, err);
  int *own = NULL;
  if (!part) {
    if (!(own = malloc(sizeof(int) * ndb))) return ss_fail(err, SS_ERR_NOMEM, "nearest neighbours: out of memory");
    ss_status st = ss_nn_partition(ndb, d, db, lddb, nc, own, err);
    if (st) {
      free(own);
      return st;
    }
  }
  nn_index t;
  int fail = index_build(ndb, d, db, lddb, nc, part ? part : own, &t);
  free(own);
  if (!fail) {
    fail = search(&t, ndb, nq, q, ldq, guess, idx, dist2);
    index_free(&t);
  }
  if (fail) return ss_fail(err, SS_ERR_NOMEM, "nearest neighbours: out of memory");
  return SS_OK;
}

ss_status ss_nn_exact(int ndb, int nq, int d, const double *db, int lddb, const double *q, int ldq, int *idx,
                      double *dist2, ss_error *err) {
  return ss_nn_exact_guided(ndb, nq, d, db, lddb, q, ldq, NULL, NULL, idx, dist2, err);
}

/* ---- Brute force ----------------------------------------------------------------------------
 *
 *
 * Brute force through BLAS: for a block of queries and a block of database points, one dgemm gives
 * q·b and the squared distance is ‖q‖² − 2 q·b + ‖b‖². That formula loses digits when ‖q‖, ‖b‖ are
 * large compared with their distance, so each query keeps every candidate whose approximate value is
 * within a rounding bound of its running minimum and the winner is decided on exact Σ (q_j − b_j)². */
#define NN_QB 256  /* queries per block */
#define NN_BB 2048 /* database points per block */
#define NN_NC 8    /* candidate slots per query before falling back to an exact scan */

typedef struct nn_state {
  double best;    /* approximate minimum of ‖b‖² − 2 q·b */
  int nc;         /* candidates kept, −1 = overflow */
  int cand[NN_NC];
  double cval[NN_NC];
} nn_state;

static double exact_d2(int d, const double *db, int lddb, int b, const double *q, int ldq, int i) {
  double s = 0;
  for (int j = 0; j < d; j++) {
    double t = q[i + (size_t)ldq * j] - db[b + (size_t)lddb * j];
    s += t * t;
  }
  return s;
}

ss_status ss_nn_brute(int ndb, int nq, int d, const double *db, int lddb, const double *q, int ldq, int *idx,
                      double *dist2, ss_error *err) {
  if (ndb < 1 || nq < 0 || d < 1 || lddb < ndb || ldq < nq)
    return ss_fail(err, SS_ERR_INVALID, "nearest neighbours: bad sizes (ndb %d, nq %d, d %d)", ndb, nq, d);
  if (nq == 0) return SS_OK;
  if (!db || !q || !idx) return ss_fail(err, SS_ERR_INVALID, "nearest neighbours: NULL array");
  double *bn = malloc(sizeof(double) * (size_t)ndb), *qn = malloc(sizeof(double) * (size_t)nq);
  double *S = malloc(sizeof(double) * (size_t)NN_QB * NN_BB);
  nn_state *stt = malloc(sizeof(nn_state) * (size_t)NN_QB);
  if (!bn || !qn || !S || !stt) {
    free(bn); free(qn); free(S); free(stt);
    return ss_fail(err, SS_ERR_NOMEM, "nearest neighbours: out of memory");
  }
  double bmax = 0;
  for (int b = 0; b < ndb; b++) bn[b] = 0;
  for (int j = 0; j < d; j++)
    for (int b = 0; b < ndb; b++) bn[b] += db[b + (size_t)lddb * j] * db[b + (size_t)lddb * j];
  for (int b = 0; b < ndb; b++) bmax = fmax(bmax, bn[b]);
  for (int i = 0; i < nq; i++) qn[i] = 0;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < nq; i++) qn[i] += q[i + (size_t)ldq * j] * q[i + (size_t)ldq * j];

  for (int q0 = 0; q0 < nq; q0 += NN_QB) {
    int mq = nq - q0 < NN_QB ? nq - q0 : NN_QB;
    for (int i = 0; i < mq; i++) { stt[i].best = INFINITY; stt[i].nc = 0; }
    for (int b0 = 0; b0 < ndb; b0 += NN_BB) {
      int mb = ndb - b0 < NN_BB ? ndb - b0 : NN_BB;
      /* S (mq x mb) = Q_blk B_blkᵀ */
      cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, mq, mb, d, 1.0, q + q0, ldq, db + b0, lddb, 0.0, S, mq);
#pragma omp parallel for schedule(static)
      for (int i = 0; i < mq; i++) {
        nn_state *s = stt + i;
        /* rounding bound of the expanded formula, with a wide safety factor */
        double tol = 1e-12 * (d + 8) * (qn[q0 + i] + bmax);
        for (int bb = 0; bb < mb; bb++) {
          double v = bn[b0 + bb] - 2.0 * S[i + (size_t)mq * bb];
          if (v > s->best + tol) continue;
          if (v < s->best) {
            s->best = v;
            if (s->nc >= 0) { /* drop candidates no longer within tol of the new minimum */
              int w = 0;
              for (int c = 0; c < s->nc; c++)
                if (s->cval[c] <= v + tol) { s->cand[w] = s->cand[c]; s->cval[w] = s->cval[c]; w++; }
              s->nc = w;
            }
          }
          if (s->nc >= 0) {
            if (s->nc < NN_NC) { s->cand[s->nc] = b0 + bb; s->cval[s->nc] = v; s->nc++; }
            else s->nc = -1;
          }
        }
      }
    }
#pragma omp parallel for schedule(dynamic, 16)
    for (int i = 0; i < mq; i++) {
      nn_state *s = stt + i;
      int qi = q0 + i, bi = -1;
      double bd = INFINITY;
      if (s->nc > 0) {
        for (int c = 0; c < s->nc; c++) {
          double e = exact_d2(d, db, lddb, s->cand[c], q, ldq, qi);
          if (e < bd || (e == bd && s->cand[c] < bi)) { bd = e; bi = s->cand[c]; }
        }
      } else { /* many near-ties (or NaN): settle it exactly over the whole database */
        for (int b = 0; b < ndb; b++) {
          double e = exact_d2(d, db, lddb, b, q, ldq, qi);
          if (e < bd) { bd = e; bi = b; }
        }
        if (bi < 0) bi = 0;
      }
      idx[qi] = bi;
      if (dist2) dist2[qi] = bd;
    }
  }
  free(bn);
  free(qn);
  free(S);
  free(stt);
  return SS_OK;
}
