/* Private: the meshes ss_match matches in place of its inputs, each an ssi_submesh of its input
 * (submesh/submesh.h), and the lift of a match back to the inputs (match_submesh.c).
 * - Kept components. The functional map is only determined on components that hold a landmark
 *   (elsewhere the probes leave the basis functions free: "dsposv info N"). So ss_match keeps, on
 *   each mesh, the components that hold a landmark — the body of a scan, without its crumbs — and
 *   matches those; a vertex of X on a dropped component takes the image of its nearest (Euclidean)
 *   kept vertex of X, and no vertex of X maps to a dropped vertex of Y.
 * - Proxies. A mesh above SSI_COARSEN_ABOVE_NV vertices is decimated to SSI_MATCH_PROXY_FACES faces
 *   (closed, manifold, oriented meshes only; others are matched as they are) and the whole match
 *   (segmentation, spectrum, functional map, refinement) runs on the proxies: vertex i of X maps
 *   through its coarse vertex to a coarse vertex of Y, i.e. the input vertex of Y it was. Landmarks
 *   move to their coarse vertices. Used by ss_match_warn and by prepared shapes (which store it), so
 *   both match a large mesh the same way. */
#ifndef SS_MATCH_SUBMESH_H
#define SS_MATCH_SUBMESH_H

#include "specseg/match.h"
#include "submesh/submesh.h"

typedef struct ssi_kept {
  ssi_submesh sub;   /* the kept components (vertices in input order); sub.active 0: the whole mesh */
  int nc, nkept;     /* components, kept components */
  int landmark_free; /* kept: the largest component (no landmarks) */
  double area, kept_area;
} ssi_kept;

void ssi_kept_free(ssi_kept *k);
/* The components of m (named `name` in messages) that hold one of the nl landmarks lm (nl = 0: the
 * largest by area); k->sub.active = 0 when that is every component. SS_ERR_INVALID for a face index
 * out of range or, with several components, unreferenced vertices. */
ss_status ssi_keep_landmark_components(const ss_mesh *m, const char *name, int nl, const int *lm, ssi_kept *k,
                                       ss_error *err);
/* Appends to w (size bytes) what was dropped of m, when anything was. */
void ssi_kept_warning(const ssi_kept *k, const ss_mesh *m, const char *name, int is_x, char *w, size_t size);

/* The proxy of m (p->active = 0 when m is matched as it is); lm (nl input vertices, may be NULL
 * when nl = 0) are moved to their coarse vertices in place. Fails only for lack of memory. */
ss_status ssi_proxy_make(const ss_mesh *m, int nl, int *lm, ssi_submesh *p, ss_error *err);

/* out (computed on sx's and sy's meshes; inactive ones stand for their own inputs) -> on the inputs:
 * the map of X's vertices (a vertex of X off sx's mesh takes the image of its nearest vertex on it)
 * and the paired centres. */
ss_status ssi_match_lift(const ssi_submesh *sx, const ssi_submesh *sy, const ss_mesh *X, ss_match_result *out,
                         ss_error *err);

#endif
