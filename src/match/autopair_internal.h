/* Internals of the landmark-free pairing shared with tests and benchmarks. */
#ifndef SS_AUTOPAIR_INTERNAL_H
#define SS_AUTOPAIR_INTERNAL_H

#include "specseg/match.h"

/* The orientation test (match.h) of the pairing p: centre a of A -> centre p[a] of B (A->m <= B->m):
 * the orientation score of the small functional map's point map A -> B. */
ss_status ssi_autopair_orient_score(const ss_centre_signature *A, const ss_centre_signature *B, const int *p,
                                    const ss_autopair_options *o, double *score, ss_error *err);

/* The second orientation test (ss_autopair_options.recheck_*) of the pairing p. */
ss_status ssi_autopair_recheck_score(const ss_centre_signature *A, const ss_centre_signature *B, const int *p,
                                     const ss_autopair_options *o, double *score, ss_error *err);

/* Orientation of a point map T: A -> B (A's nv entries): over A's faces whose image triangle is not
 * degenerate, (preserved − reversed) / count, against B's outward normals. */
double ssi_map_orientation(const ss_centre_signature *A, const ss_centre_signature *B, const int *T);

/* experimental: the point map of the candidate's small functional map (basis k) and its score */
ss_status ssi_autopair_orient_map(const ss_centre_signature *A, const ss_centre_signature *B, const int *p,
                                  const ss_autopair_options *o, int k, double *score, int *T, ss_error *err);
/* per-vertex unit tangent gradients of the centres' exact distance fields, nv x m x 3 (malloc'd) */
ss_status ssi_centre_gradients(const ss_centre_signature *sg, double **G, ss_error *err);
void ssi_field_gradients(const ss_mesh *mesh, const double *normals, int n, int m, const double *F, double *G);
/* pseudo-scalar agreement of the pairing p through the point map T (A -> B; NULL: identity) */
double ssi_pseudo_score(const ss_centre_signature *A, const double *GA, const ss_centre_signature *B, const double *GB,
                        const int *p, const int *T, double keep);
double ssi_pseudo_centres(const ss_centre_signature *A, const double *GA, const ss_centre_signature *B, const double *GB,
                          const int *p);
#endif
