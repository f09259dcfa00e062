/* Left–right symmetry map of an approximately mirror-symmetric shape (FAUST's "sym" rows of Table 1):
 * an extrinsic mirror plane fitted by ICP, then an intrinsic check on landmark distances. */
#include "specseg/eval.h"
#include "specseg/geodesic.h"
#include "specseg/streamline.h"

#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void reflect(const double *n, const double *c, const double *p, double *q) {
  double t = 2 * ((p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1] + (p[2] - c[2]) * n[2]);
  for (int k = 0; k < 3; k++) q[k] = p[k] - t * n[k];
}

/* Fits the plane that best swaps x and sym(x): normal = principal direction of x − sym(x) (sign kept
 * close to the previous normal), point = mean of the midpoints. */
static int refit(const ss_mesh *m, const int *sym, double *n, double *c) {
  double S[9] = {0}, mid[3] = {0};
  for (int x = 0; x < m->nv; x++) {
    const double *a = m->V + 3 * x, *b = m->V + 3 * sym[x];
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    for (int i = 0; i < 3; i++) {
      mid[i] += 0.5 * (a[i] + b[i]);
      for (int j = 0; j < 3; j++) S[i + 3 * j] += d[i] * d[j];
    }
  }
  double w[3];
  if (LAPACKE_dsyev(LAPACK_COL_MAJOR, 'V', 'U', 3, S, 3, w) != 0) return 1;
  double *e = S + 6; /* eigenvector of the largest eigenvalue */
  double dot = e[0] * n[0] + e[1] * n[1] + e[2] * n[2], s = dot < 0 ? -1 : 1;
  double len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  if (!(len > 0)) return 1;
  for (int i = 0; i < 3; i++) n[i] = s * e[i] / len, c[i] = mid[i] / m->nv;
  return 0;
}

ss_status ss_symmetry_map(const ss_mesh *m, int nl, const int *lm, const int *lm_mirror, int *sym,
                          ss_symmetry_stats *stats, ss_error *err) {
  if (!m || m->nv < 2 || !sym || nl < 1 || !lm || !lm_mirror)
    return ss_fail(err, SS_ERR_INVALID, "symmetry: bad arguments");
  const int nv = m->nv;
  for (int i = 0; i < nl; i++)
    if (lm[i] < 0 || lm[i] >= nv || lm_mirror[i] < 0 || lm_mirror[i] >= nv)
      return ss_fail(err, SS_ERR_INVALID, "symmetry: landmark %d outside [0,%d)", i, nv);
  double n[3] = {0}, c[3] = {0};
  /* each pair is listed both ways round; orient every difference like the first one so they add */
  for (int i = 0; i < nl; i++) {
    double d[3], dot = 0;
    for (int k = 0; k < 3; k++) d[k] = m->V[3 * lm[i] + k] - m->V[3 * lm_mirror[i] + k], dot += d[k] * n[k];
    double s = dot < 0 ? -1 : 1;
    for (int k = 0; k < 3; k++) n[k] += s * d[k];
  }
  double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0)) return ss_fail(err, SS_ERR_INVALID, "symmetry: the landmark pairs give no left-right direction");
  for (int k = 0; k < 3; k++) n[k] /= len;
  for (int x = 0; x < nv; x++)
    for (int k = 0; k < 3; k++) c[k] += m->V[3 * x + k] / nv;

  ss_status st = SS_OK;
  const int K = nv < 8 ? nv : 8;
  double *R = malloc(sizeof(double) * 3 * (size_t)nv);
  double *F = malloc(sizeof(double) * (size_t)nv * nl), *G = malloc(sizeof(double) * (size_t)nv * nl);
  ss_geodesic_mesh *gm = NULL;
  if (!R || !F || !G) { st = ss_fail(err, SS_ERR_NOMEM, "symmetry: out of memory"); goto done; }
  for (int it = 0; it < 10; it++) {
    for (int x = 0; x < nv; x++) reflect(n, c, m->V + 3 * x, R + 3 * x);
    if ((st = ss_closest_vertices(R, nv, m, sym, err))) goto done;
    if (refit(m, sym, n, c)) { st = ss_fail(err, SS_ERR_NUMERIC, "symmetry: plane fit failed"); goto done; }
  }
  for (int x = 0; x < nv; x++) reflect(n, c, m->V + 3 * x, R + 3 * x);

  /* intrinsic check: x's distance to landmark i must equal sym(x)'s distance to its mirror */
  if ((st = ss_geodesic_mesh_build(m, &gm, err))) goto done;
  if ((st = ss_geodesic_fields(gm, lm, nl, 0, F, err))) goto done;
  if ((st = ss_geodesic_fields(gm, lm_mirror, nl, 0, G, err))) goto done;
  double area = ss_mesh_area(m), diag = ss_mesh_bbox_diagonal(m), res = 0;
  int changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed, res)
  for (int x = 0; x < nv; x++) {
    int cand[8] = {0};
    double cd[8] = {0};
    int nc = 0;
    const double *q = R + 3 * x;
    for (int y = 0; y < nv; y++) { /* K nearest by insertion (ties: lower index first) */
      const double *p = m->V + 3 * y;
      double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
      if (nc == K && d2 >= cd[K - 1]) continue;
      int j = nc < K ? nc++ : K - 1;
      while (j > 0 && cd[j - 1] > d2) cand[j] = cand[j - 1], cd[j] = cd[j - 1], j--;
      cand[j] = y, cd[j] = d2;
    }
    int best = nc > 0 ? cand[0] : x;
    double bc = INFINITY;
    for (int j = 0; j < nc; j++) {
      int y = cand[j];
      double e = cd[j];
      for (int i = 0; i < nl; i++) {
        double dd = F[x + (size_t)nv * i] - G[y + (size_t)nv * i];
        e += isfinite(dd) ? dd * dd : 0;
      }
      e /= area;
      if (e < bc) bc = e, best = y;
    }
    changed += best != sym[x];
    sym[x] = best;
    res += sqrt(cd[0]) / diag;
  }
  if (stats) {
    memcpy(stats->normal, n, sizeof n);
    memcpy(stats->point, c, sizeof c);
    int inv = 0;
    for (int x = 0; x < nv; x++) inv += sym[sym[x]] == x;
    stats->involution = (double)inv / nv;
    stats->mean_residual = res / nv;
    stats->refined = changed;
  }
done:
  ss_geodesic_mesh_free(gm);
  free(R);
  free(F);
  free(G);
  return st;
}
