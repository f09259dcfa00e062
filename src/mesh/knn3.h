/* Internal: the k nearest of a fixed set of 3D points, by a kd-tree built once (median splits on the
 * widest axis, leaves of at most 8 points). Exact: the same neighbours, in the same order (distance,
 * then index on ties), as a scan over every point. Not part of the public API. */
#ifndef SS_MESH_KNN3_H
#define SS_MESH_KNN3_H

#include "specseg/core.h"

typedef struct ssi_knn3 ssi_knn3;

/* The tree over n points P (3n doubles, xyz; borrowed: must outlive the tree). n >= 1. */
ss_status ssi_knn3_build(int n, const double *P, ssi_knn3 **out, ss_error *err);

/* The k nearest points to q (k <= n), nearest first, into idx (k ints); d2 (k doubles, may be NULL)
 * their squared distances (NULL: k at most 64). Reads the tree only: calls may run at the same time from different
 * threads. */
void ssi_knn3_query(const ssi_knn3 *t, const double q[3], int k, int *idx, double *d2);

void ssi_knn3_free(ssi_knn3 *t);

#endif
