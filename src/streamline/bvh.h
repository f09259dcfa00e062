/* Private: bounding-volume hierarchy over the triangles of a mesh, for exact closest-point queries
 * (projection onto the input surface while remeshing, and deviation measurements). */
#ifndef SS_STREAMLINE_BVH_H
#define SS_STREAMLINE_BVH_H

#include "specseg/core.h"

typedef struct ssi_bvh_node {
  double lo[3], hi[3];
  int left;        /* internal: index of the left child (right = left + 1); leaf: -1 */
  int first, count; /* leaf: range in tri[] */
} ssi_bvh_node;

typedef struct ssi_bvh {
  const double *V; /* borrowed from the mesh */
  const int *F;
  int nf, nnodes;
  ssi_bvh_node *nodes;
  int *tri;        /* triangle order, leaves point into it */
} ssi_bvh;

ss_status ssi_bvh_build(const ss_mesh *m, ssi_bvh *b, ss_error *err);
void ssi_bvh_free(ssi_bvh *b);

/* Closest point of the surface to p. `hint` (a triangle index or -1) seeds the search bound: with a
 * nearby hint the traversal prunes almost everything. Writes the point to q (may be NULL) and
 * returns the triangle; *d2 receives the squared distance. */
int ssi_bvh_closest(const ssi_bvh *b, const double p[3], int hint, double q[3], double *d2);

/* Closest point of triangle (a, b, c) to p. */
void ssi_closest_point_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                               double q[3]);

#endif
