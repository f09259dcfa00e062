/* Sub-meshes of an input mesh and the lifts of their results back to it (see submesh.h). */
#include "submesh/submesh.h"
#include "specseg/streamline.h"
#include "streamline/decimate.h"

#include <stdlib.h>
#include <string.h>

void ssi_submesh_free(ssi_submesh *s) {
  if (!s) return;
  ss_mesh_free(&s->mesh);
  free(s->to_sub);
  free(s->to_in);
  memset(s, 0, sizeof *s);
}

ss_status ssi_submesh_components(const ss_mesh *m, const int *comp, const unsigned char *keep, ssi_submesh *s,
                                 ss_error *err) {
  memset(s, 0, sizeof *s);
  int nv = 0, nf = 0;
  for (int i = 0; i < m->nv; i++) nv += comp[i] >= 0 && keep[comp[i]];
  for (int f = 0; f < m->nf; f++) nf += keep[comp[m->F[3 * (size_t)f]]];
  s->to_sub = malloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
  s->to_in = malloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
  ss_status st = !s->to_sub || !s->to_in ? ss_fail(err, SS_ERR_NOMEM, "submesh: out of memory")
                                          : ss_mesh_alloc(&s->mesh, nv, nf, err);
  if (st) {
    ssi_submesh_free(s);
    return st;
  }
  nv = 0;
  for (int i = 0; i < m->nv; i++) {
    const int in = comp[i] >= 0 && keep[comp[i]];
    s->to_sub[i] = in ? nv : -1;
    if (in) {
      memcpy(s->mesh.V + 3 * (size_t)nv, m->V + 3 * (size_t)i, sizeof(double) * 3);
      s->to_in[nv++] = i;
    }
  }
  nf = 0;
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * (size_t)f;
    if (!keep[comp[t[0]]]) continue;
    for (int j = 0; j < 3; j++) s->mesh.F[3 * (size_t)nf + j] = s->to_sub[t[j]];
    nf++;
  }
  s->active = 1;
  return SS_OK;
}

ss_status ssi_submesh_decimate(const ss_mesh *m, int target_faces, ssi_submesh *s, ss_error *err) {
  memset(s, 0, sizeof *s);
  s->to_sub = malloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
  if (!s->to_sub) return ss_fail(err, SS_ERR_NOMEM, "submesh: out of memory");
  ss_status st = ssi_decimate(m, target_faces, &s->mesh, s->to_sub, &s->to_in, err);
  if (st) ssi_submesh_free(s);
  else s->active = 1;
  return st;
}

void ssi_submesh_restrict(const ssi_submesh *s, int n_in, int ncols, const double *in, double *out) {
  const int n_sub = s->mesh.nv;
  for (int j = 0; j < ncols; j++)
    for (int i = 0; i < n_sub; i++) out[i + (size_t)n_sub * j] = in[s->to_in[i] + (size_t)n_in * j];
}

void ssi_submesh_lift_values(const ssi_submesh *s, int n_in, const int *v_sub, int *v_in) {
  for (int i = 0; i < n_in; i++) {
    const int v = ssi_submesh_sub_vertex(s, i);
    v_in[i] = v >= 0 ? v_sub[v] : -1;
  }
}

void ssi_submesh_lift_indices(const ssi_submesh *s, int n, int *idx) {
  if (!s->active) return;
  for (int k = 0; k < n; k++)
    if (idx[k] >= 0) idx[k] = s->to_in[idx[k]];
}

ss_status ssi_fill_from_nearest(const ss_mesh *m, int *v, const char *who, ss_error *err) {
  const int nv = m->nv;
  int nk = 0;
  for (int i = 0; i < nv; i++) nk += v[i] >= 0;
  const int nq = nv - nk;
  if (nq == 0) return SS_OK;
  if (nk == 0) return ss_fail(err, SS_ERR_NUMERIC, "%s: no input vertex received a label", who);
  ss_mesh kept = {0};
  double *Q = malloc(sizeof(double) * 3 * (size_t)nq);
  int *qi = malloc(sizeof(int) * (size_t)nq), *nn = malloc(sizeof(int) * (size_t)nq);
  int *kidx = malloc(sizeof(int) * (size_t)nk);
  ss_status st = SS_OK;
  if (!Q || !qi || !nn || !kidx || ss_mesh_alloc(&kept, nk, 0, NULL)) {
    st = ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", who);
    goto done;
  }
  int a = 0, b = 0;
  for (int i = 0; i < nv; i++) {
    if (v[i] >= 0) {
      memcpy(kept.V + 3 * (size_t)a, m->V + 3 * (size_t)i, 3 * sizeof(double));
      kidx[a++] = i;
    } else {
      memcpy(Q + 3 * (size_t)b, m->V + 3 * (size_t)i, 3 * sizeof(double));
      qi[b++] = i;
    }
  }
  st = ss_closest_vertices(Q, nq, &kept, nn, err);
  if (!st)
    for (int q = 0; q < nq; q++) v[qi[q]] = v[kidx[nn[q]]];
done:
  free(Q), free(qi), free(nn), free(kidx), ss_mesh_free(&kept);
  return st;
}
