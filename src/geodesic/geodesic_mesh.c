/* Build the shared, read-only structure for exact geodesic propagation. */
#include "geodesic/geodesic_mesh.h"
#include "geodesic/graph_build.h"
#include "mesh/mesh_topology.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  int lo, hi, h;
} he_key;

static int cmp_key(const void *x, const void *y) {
  const he_key *a = x, *b = y;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return (a->h > b->h) - (a->h < b->h);
}

void ss_geodesic_mesh_free(ss_geodesic_mesh *gm) {
  if (!gm) return;
  free(gm->F); free(gm->V); free(gm->twin); free(gm->fr); free(gm->vptr); free(gm->vcorner); free(gm->vflag); free(gm->cang); free(gm->ang); free(gm->theta);
  free(gm);
}

int ss_geodesic_mesh_nv(const ss_geodesic_mesh *gm) { return gm ? gm->nv : 0; }

static ss_status build_oriented(const ss_mesh *m, ss_geodesic_mesh **out, ss_error *err);

/* The propagation needs consistently oriented faces (twins run an edge in opposite directions): a
 * mesh whose orientable components have some faces reversed is oriented first (face order and
 * vertex indices are kept, so the distances are those of the clean mesh); a non-orientable one is
 * refused. */
ss_status ss_geodesic_mesh_build(const ss_mesh *m, ss_geodesic_mesh **out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "null output");
  *out = NULL;
  ss_status st = ssi_graph_check_mesh(m, err);
  if (st) return st;
  if (m->nv < 1) return ss_fail(err, SS_ERR_INVALID, "empty mesh");
  int *Fo = NULL;
  if ((st = ssi_mesh_orient_copy(m, &Fo, NULL, err))) return st;
  if (!Fo) return build_oriented(m, out, err);
  ss_mesh mo = *m;
  mo.F = Fo;
  st = build_oriented(&mo, out, err);
  free(Fo);
  return st;
}

static ss_status build_oriented(const ss_mesh *m, ss_geodesic_mesh **out, ss_error *err) {
  int nv = m->nv, nf = m->nf;
  size_t nh = 3 * (size_t)nf;
  ss_geodesic_mesh *gm = calloc(1, sizeof *gm);
  if (!gm) return ss_fail(err, SS_ERR_NOMEM, "out of memory");
  gm->nv = nv; gm->nf = nf;
  gm->F = malloc(sizeof(int) * (nh ? nh : 1));
  gm->V = malloc(sizeof(double) * 3 * (size_t)nv);
  gm->twin = malloc(sizeof(int) * (nh ? nh : 1));
  gm->fr = malloc(sizeof(ssi_he_frame) * (nh ? nh : 1));
  gm->vptr = calloc((size_t)nv + 1, sizeof(int));
  gm->vcorner = malloc(sizeof(int) * (nh ? nh : 1));
  gm->vflag = calloc((size_t)nv, 1);
  gm->cang = calloc(nh ? nh : 1, sizeof(double));
  gm->ang = calloc(nh ? nh : 1, sizeof(double));
  gm->theta = calloc((size_t)nv, sizeof(double));
  he_key *keys = malloc(sizeof(he_key) * (nh ? nh : 1));
  double *angle = calloc((size_t)nv, sizeof(double));
  unsigned char *dead = calloc((size_t)nf + 1, 1);
  if (!gm->F || !gm->V || !gm->twin || !gm->fr || !gm->vptr || !gm->vcorner || !gm->vflag || !gm->cang || !gm->ang || !gm->theta || !keys || !angle || !dead) {
    free(keys); free(angle); free(dead);
    ss_geodesic_mesh_free(gm);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory building the geodesic structure");
  }
  memcpy(gm->F, m->F, sizeof(int) * nh);
  memcpy(gm->V, m->V, sizeof(double) * 3 * (size_t)nv);
  /* the size of the surface: bounding box of the vertices faces use (an unreferenced vertex far
   * away must not set the tolerances: at 1e20 they swallowed every comparison) */
  {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t c = 0; c < nh; c++) {
      const double *p = m->V + 3 * (size_t)m->F[c];
      for (int k = 0; k < 3; k++) {
        if (p[k] < lo[k]) lo[k] = p[k];
        if (p[k] > hi[k]) hi[k] = p[k];
      }
    }
    double d2 = 0;
    for (int k = 0; k < 3 && nh > 0; k++) d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    gm->scale = sqrt(d2);
  }
  if (!(gm->scale > 0) || !isfinite(gm->scale)) gm->scale = 1;
  /* frames and angles; faces of (near) zero area, or with a repeated vertex, are cut out */
  for (int f = 0; f < nf; f++) {
    const int *t = m->F + 3 * (size_t)f;
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) dead[f] = 1;
    for (int i = 0; i < 3 && !dead[f]; i++) {
      const double *a = m->V + 3 * (size_t)t[i], *b = m->V + 3 * (size_t)t[(i + 1) % 3],
                   *c = m->V + 3 * (size_t)t[(i + 2) % 3];
      double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, q[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      double L = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      double cr[3] = {e[1] * q[2] - e[2] * q[1], e[2] * q[0] - e[0] * q[2], e[0] * q[1] - e[1] * q[0]};
      double area2 = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
      double lq = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
      if (!(L > 0) || !(area2 > 1e-14 * L * lq) || !(lq > 0)) { dead[f] = 1; break; }
      ssi_he_frame *fr = gm->fr + 3 * (size_t)f + i;
      fr->len = L;
      fr->cx = (e[0] * q[0] + e[1] * q[1] + e[2] * q[2]) / L;
      fr->cy = area2 / L;
    }
    if (!dead[f])
      for (int i = 0; i < 3; i++) {
        /* interior angle at t[i] between half-edge i and the reversed half-edge i+2 */
        const ssi_he_frame *fr = gm->fr + 3 * (size_t)f + i;
        gm->ang[3 * (size_t)f + i] = atan2(fr->cy, fr->cx);
        angle[t[i]] += gm->ang[3 * (size_t)f + i];
      }
    else
      for (int i = 0; i < 3; i++) { gm->fr[3 * (size_t)f + i].len = 0; gm->fr[3 * (size_t)f + i].cx = 0; gm->fr[3 * (size_t)f + i].cy = 0; }
  }
  /* twins: exactly two live half-edges on an edge, with opposite directions */
  size_t nk = 0;
  for (int f = 0; f < nf; f++) {
    for (int i = 0; i < 3; i++) gm->twin[3 * (size_t)f + i] = -1;
    if (dead[f]) continue;
    for (int i = 0; i < 3; i++) {
      int a = m->F[3 * (size_t)f + i], b = m->F[3 * (size_t)f + (i + 1) % 3];
      keys[nk].lo = a < b ? a : b; keys[nk].hi = a < b ? b : a; keys[nk].h = 3 * f + i;
      nk++;
    }
  }
  qsort(keys, nk, sizeof(he_key), cmp_key);
  for (size_t i = 0; i < nk;) {
    size_t j = i + 1;
    while (j < nk && keys[j].lo == keys[i].lo && keys[j].hi == keys[i].hi) j++;
    if (j - i == 2) {
      int h0 = keys[i].h, h1 = keys[i + 1].h;
      if (m->F[h0] == m->F[ssi_he_next(h1)] && m->F[h1] == m->F[ssi_he_next(h0)]) {
        gm->twin[h0] = h1; gm->twin[h1] = h0;
      }
    }
    i = j;
  }
  /* corners of live faces; pseudo-source vertices: boundary/cut or angle sum >= 2*pi (saddles; flat
   * vertices are included, which costs a few windows but never exactness) */
  for (int f = 0; f < nf; f++)
    if (!dead[f])
      for (int i = 0; i < 3; i++) gm->vptr[m->F[3 * (size_t)f + i] + 1]++;
  for (int v = 0; v < nv; v++) gm->vptr[v + 1] += gm->vptr[v];
  int *pos = malloc(sizeof(int) * (size_t)nv);
  if (!pos) {
    free(keys); free(angle); free(dead);
    ss_geodesic_mesh_free(gm);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory building the geodesic structure");
  }
  memcpy(pos, gm->vptr, sizeof(int) * (size_t)nv);
  for (int f = 0; f < nf; f++) {
    if (dead[f]) continue;
    for (int i = 0; i < 3; i++) {
      int h = 3 * f + i, v = m->F[h];
      gm->vcorner[pos[v]++] = h;
      if (gm->twin[h] < 0) { gm->vflag[v] |= SS_GV_PSEUDO; gm->vflag[m->F[ssi_he_next(h)]] |= SS_GV_PSEUDO; }
    }
  }
  for (int v = 0; v < nv; v++) {
    /* Flat vertices (angle sum 2*pi up to round-off, e.g. edge midpoints of a subdivided mesh) are
     * not pseudo-sources: geodesics cross them straight and the windows on both sides cover
     * everything but a wedge of the excess angle (< 1e-9 rad), whose effect on distances is of the
     * order of r * 1e-18. Treating them as sources would launch a needle of windows from each. */
    if (angle[v] > 2 * M_PI + 1e-9) gm->vflag[v] |= SS_GV_PSEUDO;
    gm->theta[v] = angle[v];
    if (gm->vflag[v] & SS_GV_PSEUDO) gm->vflag[v] |= SS_GV_FULL; /* cleared below when the fan is a cycle */
  }
  /* rotational order of corners: the corner after h (v->a) counter-clockwise is twin(prev(h)) */
  for (int v = 0; v < nv; v++) {
    int deg = gm->vptr[v + 1] - gm->vptr[v];
    if (deg == 0 || !(gm->vflag[v] & SS_GV_PSEUDO)) continue;
    int h0 = gm->vcorner[gm->vptr[v]], h = h0, k = 0, ok = 1;
    double cum = 0;
    do {
      gm->cang[h] = cum;
      cum += atan2(gm->fr[h].cy, gm->fr[h].cx);
      int t = gm->twin[ssi_he_prev(h)];
      if (t < 0) { ok = 0; break; }
      h = t;
      k++;
    } while (h != h0 && k <= deg);
    if (ok && h == h0 && k == deg) {
      gm->theta[v] = cum;
      gm->vflag[v] &= (unsigned char)~SS_GV_FULL;
    }
  }
  free(pos); free(keys); free(angle); free(dead);
  *out = gm;
  return SS_OK;
}
