/* Checks of a pair's landmarks against the prepared shapes (internal to src/match). */
#ifndef SS_MATCH_LANDMARK_CHECK_H
#define SS_MATCH_LANDMARK_CHECK_H
#include "specseg/match.h"

/* SS_ERR_INVALID when a landmark lies on no segmented part of its shape (a crumb: psi < 0).
 * lx, ly: the nl landmarks on the prepared meshes X, Y (proxy or sub-mesh vertices); in_x, in_y: the
 * same landmarks as the caller gave them (input vertices), for the message. */
ss_status ssi_check_landmarks_segmented(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lx,
                                        const int *ly, const int *in_x, const int *in_y, ss_error *err);
#endif
