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

#endif
