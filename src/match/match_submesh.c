/* The meshes ss_match matches in place of its inputs (the components that hold landmarks; coarse
 * proxies of very large meshes) and the lift of a match back to the inputs (see match_submesh.h). */
#include "match/match_submesh.h"
#include "util/warnings.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "streamline/decimate.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ssi_kept_free(ssi_kept *k) {
  ssi_submesh_free(&k->sub);
  memset(k, 0, sizeof *k);
}

ss_status ssi_keep_landmark_components(const ss_mesh *m, const char *name, int nl, const int *lm, ssi_kept *k,
                                       ss_error *err) {
  memset(k, 0, sizeof *k);
  if (!m->V || !m->F || m->nv < 1 || m->nf < 1) return SS_OK; /* refused by the preparation, with its message */
  for (size_t c = 0; c < 3 * (size_t)m->nf; c++)
    if (m->F[c] < 0 || m->F[c] >= m->nv)
      return ss_fail(err, SS_ERR_INVALID, "match: %s: face %zu has vertex index %d out of range [0, %d)", name, c / 3,
                     m->F[c], m->nv);
  int *comp = malloc(sizeof(int) * (size_t)m->nv);
  unsigned char *has = NULL;
  double *carea = NULL;
  ss_status st = SS_OK;
  int nc = comp ? ssi_mesh_components(m, comp) : -1;
  if (nc < 0) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
  k->nc = nc;
  if (nc <= 1) goto done;
  has = calloc((size_t)nc, 1);
  carea = calloc((size_t)nc, sizeof(double));
  if (!has || !carea) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
  int unref = 0, first_unref = -1;
  for (int i = 0; i < m->nv; i++)
    if (comp[i] < 0 && !unref++) first_unref = i;
  if (unref) {
    st = ss_fail(err, SS_ERR_INVALID,
                 "match: %s: the mesh has %d unreferenced vert%s (e.g. vertex %d); remove them first (`specseg info` "
                 "counts them): landmarks and maps refer to its vertex indices",
                 name, unref, unref == 1 ? "ex" : "ices", first_unref);
    goto done;
  }
  for (int i = 0; i < nl; i++) has[comp[lm[i]]] = 1;
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * (size_t)f;
    double a = ssi_triangle_area(m->V + 3 * (size_t)t[0], m->V + 3 * (size_t)t[1], m->V + 3 * (size_t)t[2]);
    if (isfinite(a)) carea[comp[t[0]]] += a, k->area += a;
  }
  if (nl == 0) { /* landmark-free: the largest component by area (the body of a scan) */
    int big = 0;
    k->landmark_free = 1;
    for (int c = 1; c < nc; c++)
      if (carea[c] > carea[big]) big = c;
    has[big] = 1;
  }
  for (int c = 0; c < nc; c++)
    if (has[c]) k->nkept++, k->kept_area += carea[c];
  if (k->nkept == nc) goto done; /* every component has a landmark: matched as it is */
  st = ssi_submesh_components(m, comp, has, &k->sub, err);
done:
  free(comp);
  free(has);
  free(carea);
  if (st) ssi_kept_free(k);
  return st;
}

void ssi_kept_warning(const ssi_kept *k, const ss_mesh *m, const char *name, int is_x, char *w, size_t size) {
  if (!k->sub.active) return;
  char line[400];
  int dropped = m->nv - k->sub.mesh.nv, nd = k->nc - k->nkept;
  snprintf(line, sizeof line,
           "%s: matched the %d of its %d components that %s (%d of %d vertices, %.1f%% of the area); "
           "dropped %d component%s of %d vert%s in all, %s",
           name, k->nkept, k->nc, k->landmark_free ? "is the largest" : "hold a landmark", k->sub.mesh.nv, m->nv, k->area > 0 ? 100 * k->kept_area / k->area : 0.0, nd,
           nd == 1 ? "" : "s", dropped, dropped == 1 ? "ex" : "ices",
           is_x ? "which map to the image of their nearest matched vertex" : "to which no vertex of X maps");
  ssi_warn_append(w, size, line);
}

ss_status ssi_proxy_make(const ss_mesh *m, int nl, int *lm, ssi_submesh *p, ss_error *err) {
  memset(p, 0, sizeof *p);
  if (m->nv <= SSI_COARSEN_ABOVE_NV || m->nf <= SSI_MATCH_PROXY_FACES) return SS_OK;
  ss_error e2 = {0};
  ss_status st = ssi_submesh_decimate(m, SSI_MATCH_PROXY_FACES, p, &e2);
  if (st == SS_ERR_NOMEM) return ss_fail(err, st, "%s", e2.msg);
  int ok = st == SS_OK;
  for (int i = 0; ok && i < m->nv; i++) ok = p->to_sub[i] >= 0;
  if (!ok) { /* open, non-manifold or with loose vertices: matched as it is */
    ssi_submesh_free(p);
    return SS_OK;
  }
  for (int i = 0; i < nl; i++) lm[i] = p->to_sub[lm[i]];
  return SS_OK;
}

ss_status ssi_match_lift(const ssi_submesh *sx, const ssi_submesh *sy, const ss_mesh *X, ss_match_result *out,
                         ss_error *err) {
  if (!sx->active && !sy->active) return SS_OK;
  if (sx->active) {
    int *map = malloc(sizeof(int) * (size_t)(X->nv > 0 ? X->nv : 1));
    if (!map) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
    ssi_submesh_lift_values(sx, X->nv, out->map, map);
    free(out->map);
    out->map = map;
    out->nX = X->nv;
  }
  ssi_submesh_lift_indices(sy, out->nX, out->map);
  ssi_submesh_lift_indices(sx, out->pairs.n, out->centerX);
  ssi_submesh_lift_indices(sy, out->pairs.n, out->centerY);
  /* the vertices of X off sx's mesh (on dropped components): the image of their nearest vertex on it */
  return sx->active ? ssi_fill_from_nearest(X, out->map, "match", err) : SS_OK;
}
