/* Farthest point sampling with exact geodesics (paper Appendix A). */
#include "specseg/geodesic.h"

#include <math.h>
#include <stdlib.h>

ss_status ss_fps(const ss_geodesic_mesh *gm, int seed, int m, int *points, double *mindist, ss_error *err) {
  if (!gm || !points || m < 1) return ss_fail(err, SS_ERR_INVALID, "fps: bad arguments");
  int nv = ss_geodesic_mesh_nv(gm);
  if (seed < 0 || seed >= nv) return ss_fail(err, SS_ERR_INVALID, "fps: seed %d outside [0,%d)", seed, nv);
  double *s = mindist ? mindist : malloc(sizeof(double) * (size_t)nv);
  double *d = malloc(sizeof(double) * (size_t)nv);
  ss_status st = SS_OK;
  if (!s || !d) { st = ss_fail(err, SS_ERR_NOMEM, "fps: out of memory"); goto done; }
  points[0] = seed;
  if ((st = ss_vtp_distances(gm, &seed, 1, 0, s, err))) goto done;
  for (int j = 1; j < m; j++) {
    /* s is the iVd distance of the points so far; its maximum is the next point (strict >, so
     * ties go to the lower index) */
    int best = -1;
    double bd = 0;
    for (int v = 0; v < nv; v++)
      if (isfinite(s[v]) && s[v] > bd) bd = s[v], best = v;
    if (best < 0) { st = ss_fail(err, SS_ERR_INVALID, "fps: only %d distinct reachable points", j); goto done; }
    points[j] = best;
    if (j == m - 1 && !mindist) break;
    if ((st = ss_vtp_distances(gm, &best, 1, 0, d, err))) goto done;
    for (int v = 0; v < nv; v++)
      if (d[v] < s[v]) s[v] = d[v];
  }
done:
  if (!mindist) free(s);
  free(d);
  return st;
}
