/* Quality figures of a triangle mesh: angles, valences, distance to a reference surface. */
#include "specseg/streamline.h"
#include "bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

ss_status ss_remesh_quality_measure(const ss_mesh *m, const ss_mesh *ref, ss_remesh_quality *q, ss_error *err) {
  memset(q, 0, sizeof *q);
  q->faces = m->nf;
  q->vertices = m->nv;
  if (m->nf <= 0 || m->nv <= 0) return ss_fail(err, SS_ERR_INVALID, "quality: empty mesh");
  for (int i = 0; i < 3 * m->nf; i++)
    if (m->F[i] < 0 || m->F[i] >= m->nv) return ss_fail(err, SS_ERR_INVALID, "quality: face index out of range");
  const double thr = 30.0 * M_PI / 180.0;
  int good = 0;
  double minang = INFINITY;
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * f;
    double worst = M_PI;
    for (int c = 0; c < 3; c++) {
      const double *o = m->V + 3 * t[c], *a = m->V + 3 * t[(c + 1) % 3], *b = m->V + 3 * t[(c + 2) % 3];
      double u[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]}, v[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
      double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
      double ang = atan2(sqrt(cx * cx + cy * cy + cz * cz), u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
      if (ang < worst) worst = ang;
    }
    if (worst >= thr) good++;
    if (worst < minang) minang = worst;
  }
  q->frac_min_angle_30 = (double)good / m->nf;
  q->min_angle_deg = minang * 180.0 / M_PI;

  /* valence = number of distinct neighbours */
  int *start = calloc((size_t)m->nv + 1, sizeof(int)), *nb = malloc(sizeof(int) * 6 * (size_t)m->nf);
  if (!start || !nb) { free(start); free(nb); return ss_fail(err, SS_ERR_NOMEM, "quality: out of memory"); }
  for (int i = 0; i < 3 * m->nf; i++) start[m->F[i] + 1] += 2;
  for (int v = 0; v < m->nv; v++) start[v + 1] += start[v];
  int *pos = malloc(sizeof(int) * (size_t)m->nv);
  if (!pos) { free(start); free(nb); return ss_fail(err, SS_ERR_NOMEM, "quality: out of memory"); }
  memcpy(pos, start, sizeof(int) * (size_t)m->nv);
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++) {
      int v = m->F[3 * f + c];
      nb[pos[v]++] = m->F[3 * f + (c + 1) % 3];
      nb[pos[v]++] = m->F[3 * f + (c + 2) % 3];
    }
  int six = 0, used = 0;
  for (int v = 0; v < m->nv; v++) {
    int n = start[v + 1] - start[v];
    if (!n) continue;
    used++;
    qsort(nb + start[v], n, sizeof(int), cmp_int);
    int d = 1;
    for (int i = start[v] + 1; i < start[v + 1]; i++) d += nb[i] != nb[i - 1];
    six += d == 6;
  }
  free(start); free(nb); free(pos);
  q->frac_valence_6 = used ? (double)six / used : 0;

  if (ref) {
    ssi_bvh b;
    ss_status st = ssi_bvh_build(ref, &b, err);
    if (st != SS_OK) return st;
    double diag = ss_mesh_bbox_diagonal(ref), mx = 0;
    int hint = -1;
    for (int v = 0; v < m->nv; v++) {
      double d2;
      hint = ssi_bvh_closest(&b, m->V + 3 * v, hint, NULL, &d2);
      if (d2 > mx) mx = d2;
    }
    ssi_bvh_free(&b);
    q->max_deviation = diag > 0 ? sqrt(mx) / diag : 0;
  }
  return SS_OK;
}
