/* Internal: edge incidence and vertex fans of a triangle soup, shared by ss_mesh_check and
 * ss_mesh_sanitize. Built by sorting half-edge keys (O(n log n)) and union-find over face corners.
 * Not public API. */
#ifndef SS_MESH_TOPOLOGY_H
#define SS_MESH_TOPOLOGY_H

#include <stdint.h>

#include "specseg/core.h"

/* 0: proper triangle; 1: repeated vertex index; 2: zero area (relative to its longest edge). */
int topo_face_degenerate(const ss_mesh *m, int f);

/* Connected components of the faces through shared vertices: comp[v] for every vertex (numbered by
 * lowest vertex; -1 for a vertex in no face). Returns the count, -1 on OOM. Indices must be valid. */
int ssi_mesh_components(const ss_mesh *m, int *comp);

/* Index range check: SS_ERR_INVALID naming the first bad face. */
ss_status topo_check_indices(const ss_mesh *m, ss_error *err);

/* Face vertex sets for duplicate detection: v sorted ascending, f the face index. */
typedef struct topo_tri {
  int v[3];
  int f;
} topo_tri;
/* Sorts by (v[0], v[1], v[2], f) in O(n + nv) plus per-vertex sorts (O(n log n)); equal vertex sets
 * end up adjacent with the lowest face index first. 0 ok, -1 out of memory. */
int topo_sort_tris(topo_tri *t, size_t n, int nv);
/* Fills t[] (sorted vertex sets) for the faces with three distinct indices where use is NULL or set. */
size_t topo_collect_tris(const ss_mesh *m, const unsigned char *use, topo_tri *t);

typedef struct topo {
  int nf;
  int nedges;            /* distinct undirected edges of the used faces */
  int boundary_edges;    /* edges with one incident face */
  int nonmanifold_edges; /* edges with more than two */
  int first_nm_a, first_nm_b, first_nm_count; /* the first non-manifold edge found (for messages) */
  /* corner c = 3*f + j (vertex F[c]); fan[c] = representative corner of the fan of faces around F[c]
   * that contains face f (faces glued across edges they share); -1 for faces not used. Faces on a
   * non-manifold edge are glued together too, so a "fan" count > 1 means a pinch. */
  int *fan;
  /* loop[c]: representative of the boundary loop through the fan of corner c, -1 when that fan has
   * no boundary edge. */
  int *loop;
} topo;

/* use: NULL (all faces) or nf flags; faces with a repeated vertex index are always left out. */
ss_status topo_build(const ss_mesh *m, const unsigned char *use, topo *T, ss_error *err);
void topo_free(topo *T);

/* Orientation (mesh_orient.c). Faces are glued across edges shared by exactly two used faces (three
 * distinct indices); an edge both faces run in the same direction is misoriented. */
typedef struct ssi_orientation {
  int misoriented_edges;       /* edges of two faces that traverse it in the same direction */
  int orientable;              /* 1: every component can be oriented consistently */
  int components;              /* components of the face graph (through two-face edges) */
  int nonorientable_components;
  int bad_face;                /* lowest face of the first non-orientable component, or -1 */
  int flipped_faces;           /* faces `flip` marks (orientable components only) */
  int components_flipped;      /* components with at least one flipped face */
  unsigned char *flip;         /* nf: 1 = reverse this face to orient its component consistently
                                  (each component keeps its majority orientation) */
} ssi_orientation;
/* use: NULL (all faces) or nf flags. */
ss_status ssi_mesh_orientation(const ss_mesh *m, const unsigned char *use, ssi_orientation *o, ss_error *err);
void ssi_orientation_free(ssi_orientation *o);
/* A consistently re-oriented copy of m->F in *F_out (malloc'd), or NULL when m is consistently
 * oriented already; *flipped (may be NULL) = faces reversed. SS_ERR_INVALID when not orientable. */
ss_status ssi_mesh_orient_copy(const ss_mesh *m, int **F_out, int *flipped, ss_error *err);
/* The same, then every face reversed when the total signed volume is negative: the faces wound
 * outward (for a closed surface), in *F_out (malloc'd), or NULL when m's own faces already are. */
ss_status ssi_mesh_outward_copy(const ss_mesh *m, int **F_out, ss_error *err);
/* 6 x the signed volume enclosed by m's vertices with faces F (nf x 3; m->F when F is NULL):
 * Σ p0 · (p1 × p2), positive when the faces are wound outward on a closed surface. */
double ssi_mesh_signed_volume6(const ss_mesh *m, const int *F);

#endif
