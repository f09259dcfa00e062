/* Critical points of a P1 function (paper §4.2) and the authors' ring-based clean-up. */
#include "specseg/segment.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Vertex → incident faces, CSR. */
static ss_status vertex_faces(const ss_mesh *m, int **ptr_out, int **idx_out, ss_error *err) {
  int *ptr = calloc((size_t)m->nv + 1, sizeof(int));
  int *idx = malloc(sizeof(int) * 3 * (size_t)(m->nf > 0 ? m->nf : 1));
  if (!ptr || !idx) {
    free(ptr);
    free(idx);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for the vertex-face incidence (%d faces)", m->nf);
  }
  for (int k = 0; k < 3 * m->nf; k++) ptr[m->F[k] + 1]++;
  for (int i = 0; i < m->nv; i++) ptr[i + 1] += ptr[i];
  int *fill = malloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
  if (!fill) {
    free(ptr);
    free(idx);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for the vertex-face incidence");
  }
  memcpy(fill, ptr, sizeof(int) * (size_t)m->nv);
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++) idx[fill[m->F[3 * f + c]]++] = f;
  free(fill);
  *ptr_out = ptr;
  *idx_out = idx;
  return SS_OK;
}

static ss_status check_mesh(const ss_mesh *m, const double *phi, ss_error *err) {
  if (!m || m->nv < 0 || m->nf < 0 || (m->nv > 0 && !m->V) || (m->nf > 0 && !m->F))
    return ss_fail(err, SS_ERR_INVALID, "critical points: invalid mesh");
  if (m->nv > 0 && !phi) return ss_fail(err, SS_ERR_INVALID, "critical points: phi is NULL");
  for (int k = 0; k < 3 * m->nf; k++)
    if (m->F[k] < 0 || m->F[k] >= m->nv)
      return ss_fail(err, SS_ERR_INVALID, "critical points: face %d references vertex %d (mesh has %d)", k / 3,
                     m->F[k], m->nv);
  for (int i = 0; i < m->nv; i++)
    if (!isfinite(phi[i])) return ss_fail(err, SS_ERR_INVALID, "critical points: phi[%d] is not finite", i);
  return SS_OK;
}

/* Symbolic perturbation: a vertex is "below" another when (φ, index) is lexicographically smaller. */
static inline int below(const double *phi, int a, int b) {
  return phi[a] < phi[b] || (phi[a] == phi[b] && a < b);
}

ss_status ss_vertex_gradient_norm(const ss_mesh *m, const double *phi, double *grad_norm, ss_error *err) {
  ss_status st = check_mesh(m, phi, err);
  if (st) return st;
  double *acc = calloc(4 * (size_t)(m->nv > 0 ? m->nv : 1), sizeof(double)); /* gx gy gz area */
  if (!acc) return ss_fail(err, SS_ERR_NOMEM, "out of memory for vertex gradients");
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * f;
    const double *p[3] = {m->V + 3 * t[0], m->V + 3 * t[1], m->V + 3 * t[2]};
    double u[3], v[3], n[3];
    for (int d = 0; d < 3; d++) {
      u[d] = p[1][d] - p[0][d];
      v[d] = p[2][d] - p[0][d];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (!(n2 > 0)) continue; /* degenerate face: no gradient */
    double area = 0.5 * sqrt(n2);
    /* ∇φ = Σ_i φ_i (n × e_i) / |n|², e_i the edge opposite vertex i, counter-clockwise. */
    double g[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++) {
      const double *a = p[(i + 1) % 3], *b = p[(i + 2) % 3];
      double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      double c[3] = {n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2], n[0] * e[1] - n[1] * e[0]};
      for (int d = 0; d < 3; d++) g[d] += phi[t[i]] * c[d] / n2;
    }
    for (int i = 0; i < 3; i++) {
      double *q = acc + 4 * (size_t)t[i];
      for (int d = 0; d < 3; d++) q[d] += area * g[d];
      q[3] += area;
    }
  }
  for (int i = 0; i < m->nv; i++) {
    const double *q = acc + 4 * (size_t)i;
    grad_norm[i] = q[3] > 0 ? sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) / q[3] : 0.0;
  }
  free(acc);
  return SS_OK;
}

ss_status ss_fiedler_critical_points(const ss_mesh *m, const double *phi, int cleanup_rings,
                                     signed char *type, int **points, int *npoints, int *nraw,
                                     ss_error *err) {
  if (!points || !npoints) return ss_fail(err, SS_ERR_INVALID, "critical points: NULL output");
  *points = NULL;
  *npoints = 0;
  if (cleanup_rings < 0) return ss_fail(err, SS_ERR_INVALID, "critical points: negative clean-up radius");
  ss_status st = check_mesh(m, phi, err);
  if (st) return st;
  int nv = m->nv;
  int *vfp = NULL, *vfi = NULL;
  if ((st = vertex_faces(m, &vfp, &vfi, err))) return st;
  signed char *ty = malloc((size_t)(nv > 0 ? nv : 1));
  int *list = malloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
  if (!ty || !list) {
    st = ss_fail(err, SS_ERR_NOMEM, "out of memory for critical points");
    goto done;
  }
  int n = 0;
  for (int x = 0; x < nv; x++) {
    ty[x] = SS_CRIT_REGULAR;
    if (vfp[x] == vfp[x + 1]) continue;
    int nbelow = 0, nabove = 0, straddle = 0;
    for (int k = vfp[x]; k < vfp[x + 1]; k++) {
      const int *t = m->F + 3 * vfi[k];
      int c = t[0] == x ? 0 : t[1] == x ? 1 : 2;
      int y = t[(c + 1) % 3], z = t[(c + 2) % 3];
      int by = below(phi, y, x), bz = below(phi, z, x);
      /* y == x only in a degenerate face; such a face says nothing about the order around x */
      if (y == x || z == x) continue;
      nbelow += by + bz;
      nabove += !by + !bz;
      straddle += by != bz;
    }
    if (nbelow + nabove == 0) continue;
    if (nbelow == 0) ty[x] = SS_CRIT_MIN;
    else if (nabove == 0) ty[x] = SS_CRIT_MAX;
    else if (straddle >= 4) ty[x] = SS_CRIT_SADDLE;
    if (ty[x] != SS_CRIT_REGULAR) list[n++] = x;
  }
  if (nraw) *nraw = n;

  if (cleanup_rings > 0 && n > 1) {
    double *g = malloc(sizeof(double) * (size_t)nv);
    int *stamp = malloc(sizeof(int) * (size_t)nv);
    int *queue = malloc(sizeof(int) * (size_t)nv);
    unsigned char *drop = calloc((size_t)n, 1);
    if (!g || !stamp || !queue || !drop) {
      free(g), free(stamp), free(queue), free(drop);
      st = ss_fail(err, SS_ERR_NOMEM, "out of memory for the critical-point clean-up");
      goto done;
    }
    if ((st = ss_vertex_gradient_norm(m, phi, g, err))) {
      free(g), free(stamp), free(queue), free(drop);
      goto done;
    }
    for (int i = 0; i < nv; i++) stamp[i] = -1;
    for (int a = 0; a < n; a++) {
      int c = list[a];
      /* breadth-first over mesh edges, ring by ring */
      int head = 0, tail = 0;
      queue[tail++] = c;
      stamp[c] = a;
      for (int ring = 0; ring < cleanup_rings && !drop[a]; ring++) {
        int end = tail;
        for (; head < end && !drop[a]; head++) {
          int x = queue[head];
          for (int k = vfp[x]; k < vfp[x + 1]; k++) {
            const int *t = m->F + 3 * vfi[k];
            for (int j = 0; j < 3; j++) {
              int y = t[j];
              if (stamp[y] == a) continue;
              stamp[y] = a;
              queue[tail++] = y;
              if (ty[y] != SS_CRIT_REGULAR && (g[y] < g[c] || (g[y] == g[c] && y < c))) drop[a] = 1;
            }
          }
        }
      }
    }
    /* the test above read the raw types; drop afterwards so the rule is applied simultaneously */
    int w = 0;
    for (int a = 0; a < n; a++) {
      if (drop[a]) ty[list[a]] = SS_CRIT_REGULAR;
      else list[w++] = list[a];
    }
    n = w;
    free(g), free(stamp), free(queue), free(drop);
  }

  if (type) memcpy(type, ty, (size_t)nv);
  int *shrunk = realloc(list, sizeof(int) * (size_t)(n > 0 ? n : 1)); /* NULL: keep the longer block */
  *points = shrunk ? shrunk : list;
  list = NULL;
  *npoints = n;
done:
  free(list);
  free(ty);
  free(vfp);
  free(vfi);
  return st;
}
