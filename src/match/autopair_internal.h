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

/* The share of A's segments (those with a counted face) on which T scores below thr (the orientation
 * score of each segment's faces, as above); seg: 2·A->m scratch, on return A->m per-segment scores
 * (NAN: none counted); *smin (may be NULL): the least segment score. 1 when no segment is scored. */
double ssi_map_orientation_reversed(const ss_centre_signature *A, const ss_centre_signature *B, const int *T, double thr,
                                    double *seg, double *smin);

/* Both candidates' orientation scores r1, r2 (orient_k = k, orient_descr_k = descr_k, orient_keep =
 * keep) and the decision's median margin med (> 0: p1), as ss_pair_centres_auto computes them. */
ss_status ssi_orient_pair(const ss_centre_signature *A, const ss_centre_signature *B, const int *p1, const int *p2, int k,
                          int descr_k, double keep, double *r1, double *r2, double *med, ss_error *err);
#endif
