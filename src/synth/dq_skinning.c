/* Dual-quaternion skinning (Kavan et al. 2008): blending unit dual quaternions instead of matrices
 * keeps the blended transform rigid, so joints bend without the volume loss / "candy wrapper" of
 * linear blend skinning. */
#include "synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>

/* quaternion (w, x, y, z) */
static void qmul(const double *a, const double *b, double *c) {
  c[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  c[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  c[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  c[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

/* Rotation matrix (row-major) -> unit quaternion, Shepperd's method for stability. */
static void mat_to_quat(const double *R, double *q) {
  double tr = R[0] + R[4] + R[8];
  if (tr > 0) {
    double s = 2 * sqrt(tr + 1);
    q[0] = 0.25 * s;
    q[1] = (R[7] - R[5]) / s;
    q[2] = (R[2] - R[6]) / s;
    q[3] = (R[3] - R[1]) / s;
  } else if (R[0] > R[4] && R[0] > R[8]) {
    double s = 2 * sqrt(1 + R[0] - R[4] - R[8]);
    q[0] = (R[7] - R[5]) / s;
    q[1] = 0.25 * s;
    q[2] = (R[1] + R[3]) / s;
    q[3] = (R[2] + R[6]) / s;
  } else if (R[4] > R[8]) {
    double s = 2 * sqrt(1 + R[4] - R[0] - R[8]);
    q[0] = (R[2] - R[6]) / s;
    q[1] = (R[1] + R[3]) / s;
    q[2] = 0.25 * s;
    q[3] = (R[5] + R[7]) / s;
  } else {
    double s = 2 * sqrt(1 + R[8] - R[0] - R[4]);
    q[0] = (R[3] - R[1]) / s;
    q[1] = (R[2] + R[6]) / s;
    q[2] = (R[5] + R[7]) / s;
    q[3] = 0.25 * s;
  }
}

ss_status ssi_dq_skin(int nv, const double *V0, int nb, const double *W, const ssi_rigid *T, double *V,
                     ss_error *err) {
  double *dq = malloc(sizeof(double) * 8 * (size_t)(nb > 0 ? nb : 1));
  if (!dq) return ss_fail(err, SS_ERR_NOMEM, "out of memory for skinning");
  for (int b = 0; b < nb; b++) {
    double *r = dq + 8 * b, *d = r + 4;
    mat_to_quat(T[b].R, r);
    double t[4] = {0, T[b].t[0], T[b].t[1], T[b].t[2]};
    qmul(t, r, d); /* dual part = t r / 2 */
    for (int k = 0; k < 4; k++) d[k] *= 0.5;
  }
  for (int i = 0; i < nv; i++) {
    const double *w = W + (size_t)i * nb;
    int piv = 0;
    for (int b = 1; b < nb; b++)
      if (w[b] > w[piv]) piv = b;
    double br[4] = {0, 0, 0, 0}, bd[4] = {0, 0, 0, 0};
    for (int b = 0; b < nb; b++) {
      if (w[b] == 0) continue;
      const double *r = dq + 8 * b, *p = dq + 8 * piv;
      /* q and -q are the same rotation: blend on the pivot's hemisphere */
      double s = (r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3] * p[3]) < 0 ? -w[b] : w[b];
      for (int k = 0; k < 4; k++) {
        br[k] += s * r[k];
        bd[k] += s * r[4 + k];
      }
    }
    double nr = sqrt(br[0] * br[0] + br[1] * br[1] + br[2] * br[2] + br[3] * br[3]);
    if (!(nr > 0)) { /* no weight at all: leave the vertex where it is */
      br[0] = nr = 1;
      br[1] = br[2] = br[3] = bd[0] = bd[1] = bd[2] = bd[3] = 0;
    }
    for (int k = 0; k < 4; k++) {
      br[k] /= nr;
      bd[k] /= nr;
    }
    /* translation = 2 d r*, rotation from r */
    double rc[4] = {br[0], -br[1], -br[2], -br[3]}, tq[4];
    qmul(bd, rc, tq);
    const double *x = V0 + 3 * (size_t)i;
    double xq[4] = {0, x[0], x[1], x[2]}, tmp[4], y[4];
    qmul(br, xq, tmp);
    qmul(tmp, rc, y);
    for (int d = 0; d < 3; d++) V[3 * (size_t)i + d] = y[d + 1] + 2 * tq[d + 1];
  }
  free(dq);
  return SS_OK;
}
