/* Private: coarse proxies of very large meshes (proxy.c). A mesh above SSI_COARSEN_ABOVE_NV vertices
 * is decimated to SSI_MATCH_PROXY_FACES faces (closed, manifold, oriented meshes only; others are
 * matched as they are) and the whole match (segmentation, spectrum, functional map, refinement) runs
 * on the proxies: vertex i of X maps through its coarse vertex to a coarse vertex of Y, i.e. the
 * input vertex of Y it was. Landmarks move to their coarse vertices. Used by ss_match_warn and by
 * prepared shapes (which store it), so both match a large mesh the same way. */
#ifndef SS_MATCH_PROXY_H
#define SS_MATCH_PROXY_H

#include "specseg/match.h"

typedef struct {
  int active;     /* 0: the mesh is matched as it is (small, or not decimable) */
  ss_mesh coarse;
  int *to_coarse; /* input vertex -> coarse vertex */
  int *src;       /* coarse vertex -> input vertex */
} ssi_proxy;

void ssi_proxy_free(ssi_proxy *p);
/* The proxy of m (p->active = 0 when m is matched as it is); lm (nl input vertices, may be NULL
 * when nl = 0) are moved to their coarse vertices in place. Fails only for lack of memory. */
ss_status ssi_proxy_make(const ss_mesh *m, int nl, int *lm, ssi_proxy *p, ss_error *err);
/* out (computed on the proxies; inactive ones stand for their own mesh) -> on the meshes the
 * proxies stand for: the map of X's nX_input vertices and the paired centres. */
ss_status ssi_proxy_lift(const ssi_proxy *cx, const ssi_proxy *cy, int nX_input, ss_match_result *out, ss_error *err);

#endif
