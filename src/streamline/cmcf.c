/* Conformalized mean curvature flow (Kazhdan, Solomon, Ben-Chen 2012), paper §4.1 "Smoothing".
 * The system matrix M_t + δ·W₀ always has the sparsity pattern of W₀ (M_t is diagonal), so one
 * CHOLMOD symbolic analysis serves every step; only the numeric factorisation is redone. */
#include "specseg/streamline.h"
#include "specseg/laplacian.h"
#include "mesh/mesh_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <cholmod.h>

void ss_cmcf_default_options(ss_cmcf_options *opt) {
  opt->steps = 12;
  opt->dt = 2.2e-5;
  opt->normalization = SS_CMCF_UNIT_AREA;
  opt->refactor_symbolic = 0;
}

/* Area-weighted centroid and area of the embedding X (connectivity of m). */
static void area_centroid(const ss_mesh *m, const double *X, double c[3], double *area) {
  double A = 0, s[3] = {0, 0, 0};
  for (int f = 0; f < m->nf; f++) {
    const double *a = X + 3 * m->F[3 * f], *b = X + 3 * m->F[3 * f + 1], *d = X + 3 * m->F[3 * f + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    double n0 = u[1] * v[2] - u[2] * v[1], n1 = u[2] * v[0] - u[0] * v[2], n2 = u[0] * v[1] - u[1] * v[0];
    double t = 0.5 * sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    A += t;
    for (int k = 0; k < 3; k++) s[k] += t * (a[k] + b[k] + d[k]) / 3.0;
  }
  *area = A;
  for (int k = 0; k < 3; k++) c[k] = A > 0 ? s[k] / A : 0;
}

static double bbox_diag(const double *X, int n) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      if (X[3 * i + k] < lo[k]) lo[k] = X[3 * i + k];
      if (X[3 * i + k] > hi[k]) hi[k] = X[3 * i + k];
    }
  double d = 0;
  for (int k = 0; k < 3; k++) d += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  return sqrt(d);
}

ss_status ss_cmcf_smooth(const ss_mesh *in, const ss_cmcf_options *opt_in, ss_mesh *out, ss_error *err) {
  ss_cmcf_options opt;
  if (opt_in) opt = *opt_in; else ss_cmcf_default_options(&opt);
  if (!in || !out) return ss_fail(err, SS_ERR_INVALID, "cmcf: NULL mesh");
  memset(out, 0, sizeof *out);
  if (in->nv <= 0 || in->nf <= 0) return ss_fail(err, SS_ERR_INVALID, "cmcf: empty mesh");
  if (opt.steps < 0) return ss_fail(err, SS_ERR_INVALID, "cmcf: negative number of steps (%d)", opt.steps);
  if (!(opt.dt > 0) || !isfinite(opt.dt)) return ss_fail(err, SS_ERR_INVALID, "cmcf: time step must be positive and finite (got %g)", opt.dt);
  for (int i = 0; i < 3 * in->nf; i++)
    if (in->F[i] < 0 || in->F[i] >= in->nv)
      return ss_fail(err, SS_ERR_INVALID, "cmcf: face %d has vertex index %d out of range [0,%d)", i / 3, in->F[i], in->nv);
  for (int i = 0; i < 3 * in->nv; i++)
    if (!isfinite(in->V[i])) return ss_fail(err, SS_ERR_INVALID, "cmcf: vertex %d has a non-finite coordinate", i / 3);
  ss_status st0 = ssi_mesh_check_coordinates(in, "cmcf", err);
  if (st0) return st0;

  double c_in[3], area_in;
  area_centroid(in, in->V, c_in, &area_in);
  if (!(area_in > 0)) return ss_fail(err, SS_ERR_INVALID, "cmcf: mesh has zero area");

  ss_status st = ss_mesh_copy(in, out, err);
  if (st != SS_OK) return st;
  const int n = in->nv;
  double *X = out->V;
  ss_mesh cur = *in;
  cur.V = X;

  ss_sparse W = {0};
  st = ss_cotan_stiffness(in, &W, err);
  if (st != SS_OK) { ss_mesh_free(out); return st; }

  double *Mt = malloc(sizeof(double) * n), *Wdiag = NULL;
  unsigned char *used = NULL; /* vertex belongs to a face */
  int *diagpos = malloc(sizeof(int) * n);
  cholmod_common cc;
  cholmod_start(&cc);
  cc.print = 0;               /* the library never prints: failures are reported through err */
  cc.error_handler = NULL;
  /* simplicial is faster up to ~100k vertices (paper-notes); above, the supernodal factor is (half the
   * time at 441k). ss_segment coarsens such inputs first, so this is for direct calls. */
  cc.supernodal = n > 100000 ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
  cholmod_sparse *A = NULL;
  cholmod_factor *L = NULL;
  cholmod_dense *B = NULL, *Xs = NULL;
  if (!Mt || !diagpos) { st = ss_fail(err, SS_ERR_NOMEM, "cmcf: out of memory"); goto done; }

  /* Upper triangle of W₀ (stype = 1): entries with row ≤ col, rows sorted so the diagonal is last. */
  size_t nnz = 0;
  for (int j = 0; j < n; j++)
    for (int p = W.colptr[j]; p < W.colptr[j + 1]; p++)
      if (W.rowind[p] <= j) nnz++;
  A = cholmod_allocate_sparse(n, n, nnz + n, 1, 1, 1, CHOLMOD_REAL, &cc);
  if (!A) { st = ss_fail(err, SS_ERR_NOMEM, "cmcf: out of memory (CHOLMOD matrix)"); goto done; }
  {
    int *Ap = A->p, *Ai = A->i;
    double *Ax = A->x;
    size_t q = 0;
    for (int j = 0; j < n; j++) {
      Ap[j] = (int)q;
      int have_diag = 0;
      for (int p = W.colptr[j]; p < W.colptr[j + 1]; p++) {
        int i = W.rowind[p];
        if (i > j) break;
        Ai[q] = i; Ax[q] = opt.dt * W.val[p];
        if (i == j) { diagpos[j] = (int)q; have_diag = 1; }
        q++;
      }
      if (!have_diag) { Ai[q] = j; Ax[q] = 0; diagpos[j] = (int)q; q++; } /* isolated vertex */
    }
    Ap[n] = (int)q;
  }
  /* keep δ·W₀'s diagonal: the numeric values are rebuilt from it every step */
  Wdiag = malloc(sizeof(double) * n);
  used = calloc((size_t)n, 1);
  if (!Wdiag || !used) { st = ss_fail(err, SS_ERR_NOMEM, "cmcf: out of memory"); goto done; }
  for (int j = 0; j < n; j++) Wdiag[j] = ((double *)A->x)[diagpos[j]];
  for (int i = 0; i < 3 * in->nf; i++) used[in->F[i]] = 1;

  B = cholmod_allocate_dense(n, 3, n, CHOLMOD_REAL, &cc);
  if (!B) { st = ss_fail(err, SS_ERR_NOMEM, "cmcf: out of memory"); goto done; }

  for (int step = 0; step < opt.steps; step++) {
    /* normalise: centre and rescale so that δ is a dimensionless step */
    double c[3], area;
    area_centroid(&cur, X, c, &area);
    if (!(area > 0) || !isfinite(area)) { st = ss_fail(err, SS_ERR_NUMERIC, "cmcf: the flow degenerated at step %d (area %g)", step, area); goto done; }
    double s;
    if (opt.normalization == SS_CMCF_UNIT_BBOX) {
      for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) X[3 * i + k] -= c[k];
      s = 1.0 / bbox_diag(X, n);
      for (int i = 0; i < 3 * n; i++) X[i] *= s;
    } else {
      s = 1.0 / sqrt(area);
      for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) X[3 * i + k] = (X[3 * i + k] - c[k]) * s;
    }
    st = ss_mass_lumped(&cur, SS_MASS_BARYCENTRIC, Mt, err);
    if (st != SS_OK) { goto done; }
    double *Ax = A->x;
    for (int j = 0; j < n; j++) {
      Ax[diagpos[j]] = Wdiag[j] + Mt[j];
      /* a vertex in no face (or only in zero-area faces) has an empty row: pin it (identity row,
       * right-hand side = itself) so the matrix stays positive definite */
      if (!used[j] || !(Ax[diagpos[j]] > 0)) { Ax[diagpos[j]] = 1; Mt[j] = 1; }
    }
    if (!L || opt.refactor_symbolic) {
      if (L) cholmod_free_factor(&L, &cc);
      L = cholmod_analyze(A, &cc);
      if (!L) { st = ss_fail(err, SS_ERR_NUMERIC, "cmcf: CHOLMOD analysis failed (status %d)", cc.status); goto done; }
    }
    if (!cholmod_factorize(A, L, &cc) || cc.status != CHOLMOD_OK) {
      /* Wdiag and the rest are released once, at done: */
      if (cc.status == CHOLMOD_NOT_POSDEF && L->minor < (size_t)n) {
        int v = L->Perm ? ((const int *)L->Perm)[L->minor] : (int)L->minor;
        st = ss_fail(err, SS_ERR_NUMERIC,
                     "cmcf: the flow's system is not positive definite at step %d (pivot of vertex %d): "
                     "near-degenerate (needle) triangles there, or the flow collapsed a small piece of the "
                     "surface; drop such faces and crumbs (ss_mesh_sanitize) or use fewer / smaller steps",
                     step, v);
      } else {
        st = ss_fail(err, cc.status == CHOLMOD_OUT_OF_MEMORY ? SS_ERR_NOMEM : SS_ERR_NUMERIC,
                     "cmcf: CHOLMOD factorisation failed at step %d (status %d)", step, cc.status);
      }
      goto done;
    }
    double *Bx = B->x;
    for (int i = 0; i < n; i++)
      for (int k = 0; k < 3; k++) Bx[(size_t)k * n + i] = Mt[i] * X[3 * i + k];
    Xs = cholmod_solve(CHOLMOD_A, L, B, &cc);
    if (!Xs) { st = ss_fail(err, SS_ERR_NUMERIC, "cmcf: CHOLMOD solve failed at step %d", step); goto done; }
    const double *xs = Xs->x;
    for (int i = 0; i < n; i++)
      for (int k = 0; k < 3; k++) X[3 * i + k] = xs[(size_t)k * n + i];
    cholmod_free_dense(&Xs, &cc);
    for (int i = 0; i < 3 * n; i++)
      if (!isfinite(X[i])) { st = ss_fail(err, SS_ERR_NUMERIC, "cmcf: non-finite coordinates after step %d", step); goto done; }
  }

  /* back to the input's area and centroid */
  {
    double c[3], area;
    area_centroid(&cur, X, c, &area);
    if (!(area > 0)) { st = ss_fail(err, SS_ERR_NUMERIC, "cmcf: the flow collapsed the surface"); goto done; }
    double s = sqrt(area_in / area);
    for (int i = 0; i < n; i++)
      for (int k = 0; k < 3; k++) X[3 * i + k] = (X[3 * i + k] - c[k]) * s + c_in[k];
    /* vertices in no face are not part of the surface: they keep their input position */
    for (int j = 0; j < n; j++)
      if (!used[j])
        for (int k = 0; k < 3; k++) X[3 * j + k] = in->V[3 * j + k];
  }
  st = SS_OK;

done:
  if (Xs) cholmod_free_dense(&Xs, &cc);
  if (B) cholmod_free_dense(&B, &cc);
  if (L) cholmod_free_factor(&L, &cc);
  if (A) cholmod_free_sparse(&A, &cc);
  cholmod_finish(&cc);
  free(Mt);
  free(Wdiag);
  free(used);
  free(diagpos);
  ss_sparse_free(&W);
  if (st != SS_OK) ss_mesh_free(out);
  return st;
}
