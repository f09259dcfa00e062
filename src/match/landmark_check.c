/* A landmark must lie on the segmentation: a crumb (a component under 1% of the area) is given its
 * neighbours' segment only after the fact, so it has no segment of its own to pair. */
#include "match/landmark_check.h"

ss_status ssi_check_landmarks_segmented(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lx,
                                        const int *ly, const int *in_x, const int *in_y, ss_error *err) {
  for (int i = 0; i < 2 * nl; i++) {
    const int onx = i < nl, l = onx ? i : i - nl;
    const ss_shape_prep *p = onx ? X : Y;
    const int v = onx ? lx[l] : ly[l];
    if (p->seg.psi && p->seg.psi[v] < 0)
      return ss_fail(err, SS_ERR_INVALID,
                     "match: %s: landmark %d (vertex %d) is on no segmented part of the shape (a component under 1%% "
                     "of the area, a crumb, gets no segmentation of its own); put the landmarks on its main components",
                     onx ? "X (the first mesh)" : "Y (the second mesh)", l, onx ? in_x[l] : in_y[l]);
  }
  return SS_OK;
}
