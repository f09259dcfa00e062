/* Triangle measures robust to the scale of the coordinates, and the coordinate range check (see
 * mesh_geometry.h). */
#include "mesh/mesh_geometry.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* plain squared quantities are trusted in [2^-900, 2^900]: far from overflow and the subnormals */
#define SQ_LO 0x1p-900
#define SQ_HI 0x1p900

static int finite3(const double *p) { return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]); }

static void cross(const double *u, const double *v, double *c) {
  c[0] = u[1] * v[2] - u[2] * v[1], c[1] = u[2] * v[0] - u[0] * v[2], c[2] = u[0] * v[1] - u[1] * v[0];
}
static double dot(const double *u, const double *v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

/* Edge vectors u = q - p, v = r - p, w = r - q of the triangle scaled by 2^-e, with their largest
 * component in [0.5, 1) (all zero: e = 0). 0, or -1 for non-finite points. */
static int scaled_edges(const double *p, const double *q, const double *r, double *u, double *v, double *w, int *e) {
  *e = 0;
  if (!finite3(p) || !finite3(q) || !finite3(r)) return -1;
  int shift = 0;
  for (int i = 0; i < 3; i++) u[i] = q[i] - p[i], v[i] = r[i] - p[i], w[i] = r[i] - q[i];
  if (!finite3(u) || !finite3(v) || !finite3(w)) { /* a difference overflowed: quarter the points (exact) */
    shift = 2;
    for (int i = 0; i < 3; i++) {
      u[i] = ldexp(q[i], -2) - ldexp(p[i], -2), v[i] = ldexp(r[i], -2) - ldexp(p[i], -2);
      w[i] = ldexp(r[i], -2) - ldexp(q[i], -2);
    }
  }
  double s = 0;
  for (int i = 0; i < 3; i++) s = fmax(s, fmax(fabs(u[i]), fmax(fabs(v[i]), fabs(w[i]))));
  if (s == 0) return 0;
  int k;
  frexp(s, &k);
  for (int i = 0; i < 3; i++) u[i] = ldexp(u[i], -k), v[i] = ldexp(v[i], -k), w[i] = ldexp(w[i], -k);
  *e = k + shift;
  return 0;
}

double ssi_triangle_area(const double *p, const double *q, const double *r) {
  double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]}, w[3], c[3];
  cross(u, v, c);
  double cc = dot(c, c);
  if (cc >= SQ_LO && cc <= SQ_HI) return 0.5 * sqrt(cc);
  int e;
  if (scaled_edges(p, q, r, u, v, w, &e)) return NAN;
  cross(u, v, c);
  return ldexp(0.5 * sqrt(dot(c, c)), 2 * e);
}

void ssi_triangle_measures(const double *p, const double *q, const double *r, double *a2, double *l2, int *e) {
  double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
  double w[3] = {r[0] - q[0], r[1] - q[1], r[2] - q[2]}, c[3];
  cross(u, v, c);
  *e = 0;
  *l2 = fmax(dot(u, u), fmax(dot(v, v), dot(w, w)));
  double cc = dot(c, c);
  *a2 = sqrt(cc);
  if (*l2 >= 0x1p-450 && *l2 <= 0x1p450 && (cc == 0 || (cc >= SQ_LO && cc <= SQ_HI))) return;
  if (scaled_edges(p, q, r, u, v, w, e)) {
    *a2 = *l2 = NAN;
    return;
  }
  cross(u, v, c);
  *l2 = fmax(dot(u, u), fmax(dot(v, v), dot(w, w)));
  *a2 = sqrt(dot(c, c));
}

double ssi_box_diagonal(const double *lo, const double *hi) {
  double e[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  double s = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
  if (s >= SQ_LO && s <= SQ_HI) return sqrt(s);
  int shift = 0;
  if (!finite3(e)) { /* hi - lo overflowed */
    if (!finite3(lo) || !finite3(hi)) return NAN;
    shift = 1;
    for (int d = 0; d < 3; d++) e[d] = ldexp(hi[d], -1) - ldexp(lo[d], -1);
  }
  double mx = fmax(fabs(e[0]), fmax(fabs(e[1]), fabs(e[2])));
  if (mx == 0) return 0;
  int k;
  frexp(mx, &k);
  for (int d = 0; d < 3; d++) e[d] = ldexp(e[d], -k);
  return ldexp(sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]), k + shift);
}

ss_status ssi_mesh_check_coordinates(const ss_mesh *m, const char *what_in, ss_error *err) {
  if (!m || m->nv <= 0 || m->nf <= 0 || !m->V || !m->F) return SS_OK; /* the callers' own checks */
  char what[64] = "";
  if (what_in) snprintf(what, sizeof what, "%.60s: ", what_in);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, big = 0;
  int ibig = -1;
  for (size_t c = 0; c < 3 * (size_t)m->nf; c++) {
    int i = m->F[c];
    if (i < 0 || i >= m->nv) continue; /* index errors are the callers' */
    const double *p = m->V + 3 * (size_t)i;
    if (!finite3(p))
      return ss_fail(err, SS_ERR_INVALID,
                     "%svertex %d has a non-finite coordinate (%g, %g, %g); fix or remove it (`specseg info` "
                     "counts such vertices)",
                     what, i, p[0], p[1], p[2]);
    for (int d = 0; d < 3; d++) {
      lo[d] = fmin(lo[d], p[d]), hi[d] = fmax(hi[d], p[d]);
      if (fabs(p[d]) > big) big = fabs(p[d]), ibig = i;
    }
  }
  if (big > SSI_COORD_MAX)
    return ss_fail(err, SS_ERR_INVALID,
                   "%svertex %d has a coordinate of magnitude %.3g, beyond the supported %.0e (squared lengths and "
                   "areas would overflow a double); scale the mesh down (results scale exactly with it)",
                   what, ibig, big, SSI_COORD_MAX);
  double diag = ssi_box_diagonal(lo, hi);
  if (diag > 0 && diag < SSI_EXTENT_MIN)
    return ss_fail(err, SS_ERR_INVALID,
                   "%sthe mesh spans only %.3g (bounding-box diagonal), below the supported %.0e (squared lengths "
                   "and areas would underflow); scale the mesh up (results scale exactly with it)",
                   what, diag, SSI_EXTENT_MIN);
  return SS_OK;
}
