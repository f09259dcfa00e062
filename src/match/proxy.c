/* Coarse proxies of very large meshes (see proxy.h). */
#include "match/proxy.h"
#include "streamline/decimate.h"

#include <stdlib.h>
#include <string.h>

void ssi_proxy_free(ssi_proxy *p) {
  if (!p) return;
  ss_mesh_free(&p->coarse);
  free(p->to_coarse);
  free(p->src);
  memset(p, 0, sizeof *p);
}

ss_status ssi_proxy_make(const ss_mesh *m, int nl, int *lm, ssi_proxy *p, ss_error *err) {
  memset(p, 0, sizeof *p);
  if (m->nv <= SSI_COARSEN_ABOVE_NV || m->nf <= SSI_MATCH_PROXY_FACES) return SS_OK;
  p->to_coarse = malloc(sizeof(int) * (size_t)m->nv);
  if (!p->to_coarse) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  ss_error e2 = {0};
  ss_status st = ssi_decimate(m, SSI_MATCH_PROXY_FACES, &p->coarse, p->to_coarse, &p->src, &e2);
  if (st == SS_ERR_NOMEM) {
    ssi_proxy_free(p);
    return ss_fail(err, st, "%s", e2.msg);
  }
  int ok = st == SS_OK;
  for (int i = 0; ok && i < m->nv; i++) ok = p->to_coarse[i] >= 0;
  if (!ok) { /* open, non-manifold or with loose vertices: matched as it is */
    ssi_proxy_free(p);
    return SS_OK;
  }
  for (int i = 0; i < nl; i++) lm[i] = p->to_coarse[lm[i]];
  p->active = 1;
  return SS_OK;
}

ss_status ssi_proxy_lift(const ssi_proxy *cx, const ssi_proxy *cy, int nX_input, ss_match_result *out, ss_error *err) {
  if (!cx->active && !cy->active) return SS_OK;
  if (cx->active) {
    int *map = malloc(sizeof(int) * (size_t)nX_input);
    if (!map) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
    for (int i = 0; i < nX_input; i++) map[i] = out->map[cx->to_coarse[i]];
    free(out->map);
    out->map = map;
    out->nX = nX_input;
  }
  if (cy->active)
    for (int i = 0; i < out->nX; i++) out->map[i] = cy->src[out->map[i]];
  for (int q = 0; q < out->pairs.n; q++) {
    if (cx->active) out->centerX[q] = cx->src[out->centerX[q]];
    if (cy->active) out->centerY[q] = cy->src[out->centerY[q]];
  }
  return SS_OK;
}
