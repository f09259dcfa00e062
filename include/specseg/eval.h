/* specseg — evaluation measures. */
#ifndef SPECSEG_EVAL_H
#define SPECSEG_EVAL_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Coherency of a segmentation of Y with the segmentation of a reference shape X0 (paper §5): for
 * every vertex y of Y, with u the centre of y's segment, the check passes when GT(y) and GT(u) lie in
 * the same segment of X0. Returns the fraction of vertices that pass in *coherency.
 *   labels0: nv0 labels of X0 (any integers; only equality matters).
 *   labels:  nv labels of Y, each in [0, m); centers: m vertices of Y (the centre of each segment).
 *   gt:      nv vertices of X0 (GT(y)); NULL = identity (then nv must equal nv0).
 * Fails with SS_ERR_INVALID on out-of-range labels, centres or map entries. */
ss_status ss_coherency(const int *labels0, int nv0, const int *labels, const int *centers, int m, int nv,
                       const int *gt, double *coherency, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
