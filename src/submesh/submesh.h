/* Private: a mesh derived from an input mesh (some of its components, or its decimation) with the
 * vertex correspondences both ways, so that work done on it is lifted back to the input (submesh.c).
 * Used by the segmentation (each significant component on its own; a very large input coarsened
 * before the flow) and by the match (the components that hold landmarks; coarse proxies of very
 * large meshes, match/match_submesh.h). */
#ifndef SS_SUBMESH_SUBMESH_H
#define SS_SUBMESH_SUBMESH_H

#include "specseg/core.h"

typedef struct ssi_submesh {
  int active;   /* 0: the input stands for itself (nothing below is set) */
  ss_mesh mesh; /* the sub-mesh */
  int *to_sub;  /* input vertex -> sub-mesh vertex; -1: none (a dropped component, a vertex in no face) */
  int *to_in;   /* sub-mesh vertex -> the input vertex it was */
} ssi_submesh;

void ssi_submesh_free(ssi_submesh *s);

/* The faces of m on the components c with keep[c] (comp: ssi_mesh_components's numbering of m's
 * vertices, -1 for a vertex in no face), faces and vertices in input order. s->active = 1. */
ss_status ssi_submesh_components(const ss_mesh *m, const int *comp, const unsigned char *keep, ssi_submesh *s,
                                 ss_error *err);

/* m decimated to about target_faces faces, topology kept (ssi_decimate: m closed, manifold and
 * oriented, else its error); to_sub: each input vertex's nearest coarse vertex (-1: in no face).
 * s->active = 1 on success; on failure s is empty. */
ss_status ssi_submesh_decimate(const ss_mesh *m, int target_faces, ssi_submesh *s, ss_error *err);

/* The vertex of the sub-mesh that input vertex i maps to (-1: none), and the input vertex that
 * sub-mesh vertex v was; both the identity when s is not active. */
static inline int ssi_submesh_sub_vertex(const ssi_submesh *s, int i) { return s->active ? s->to_sub[i] : i; }
static inline int ssi_submesh_input_vertex(const ssi_submesh *s, int v) { return s->active ? s->to_in[v] : v; }

/* Restriction: per-vertex columns on the input (ncols columns of n_in rows, column-major) -> the
 * same columns on the sub-mesh's vertices (ncols columns of s->mesh.nv rows). s active. */
void ssi_submesh_restrict(const ssi_submesh *s, int n_in, int ncols, const double *in, double *out);

/* Lifts: per-vertex values on the sub-mesh -> per input vertex (n_in of them), -1 where the input
 * vertex maps to none; vertex indices of the sub-mesh (n, in place; negative entries stay) -> the
 * input vertices they were. Both copy / leave the values as they are when s is not active. */
void ssi_submesh_lift_values(const ssi_submesh *s, int n_in, const int *v_sub, int *v_in);
void ssi_submesh_lift_indices(const ssi_submesh *s, int n, int *idx);

/* v (m->nv values): every negative entry takes the value of the nearest vertex (Euclidean, m's
 * positions) whose entry is not negative: the lift of the vertices a sub-mesh left out. who: the
 * messages' prefix ("segment", "match"). SS_ERR_NUMERIC when no entry is set. */
ss_status ssi_fill_from_nearest(const ss_mesh *m, int *v, const char *who, ss_error *err);

#endif
