/* Private: the editable triangle mesh used by the isotropic remesher. Flat arrays, corner-table
 * half-edges: half-edge h = 3f + k runs from F[h] to F[next(h)] inside face f; opp[h] is its twin.
 * Dead faces/vertices are flagged and dropped by rm_compact(). Closed, edge-manifold, consistently
 * oriented meshes only. */
#ifndef SS_STREAMLINE_REMESH_MESH_H
#define SS_STREAMLINE_REMESH_MESH_H

#include "specseg/core.h"

typedef struct rm_mesh {
  int nv, nf;          /* slots in use (dead ones included until compaction) */
  int cap_v, cap_f;
  double *V;           /* 3*cap_v */
  int *F, *opp;        /* 3*cap_f */
  int *vh;             /* cap_v: one outgoing half-edge of each live vertex */
  int *val;            /* cap_v: valence */
  int *hint;           /* cap_v: triangle of the reference surface last closest to the vertex */
  int *mark;           /* cap_v: scratch stamps */
  int stamp;
  unsigned char *vdead, *fdead;
  int *scratch;        /* max(cap_v, cap_f) ints for compaction */
} rm_mesh;

static inline int rm_next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
static inline int rm_prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }

/* Copies `in`, links twins, checks it is closed, edge- and vertex-manifold and oriented. */
ss_status rm_init(rm_mesh *m, const ss_mesh *in, ss_error *err);
void rm_free(rm_mesh *m);
ss_status rm_reserve(rm_mesh *m, int nv, int nf, ss_error *err);

/* Passes; each returns the number of operations done (or -1 on allocation failure for split). */
int rm_split_long(rm_mesh *m, double hi, ss_error *err);
int rm_collapse_short(rm_mesh *m, double lo, double hi);
int rm_flip_valence(rm_mesh *m);
/* Split the longest (or collapse the shortest) edges until the live face count is within one
 * operation (2 faces) of `target`. Returns the number of operations, -1 on allocation failure. */
int rm_adjust_count(rm_mesh *m, int target, double hi, ss_error *err);
void rm_compact(rm_mesh *m);
/* May the edge of half-edge h collapse without changing the topology? (link condition: v0 and v1
 * share exactly the two neighbours opposite the edge, each of valence > 3.) Uses the mark stamps. */
int rm_link_ok(rm_mesh *m, int h);
/* Remove v0 = F[h], merge it into v1 = F[next(h)], placed at p (3 doubles). The faces of h and its
 * twin die; no geometric check (the caller's). */
void rm_collapse_edge(rm_mesh *m, int h, const double *p);
int rm_live_faces(const rm_mesh *m);

#endif
