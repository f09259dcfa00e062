/* Table 1 of a manifest's rows: means per group, landmark set and method. */
#include "specseg/eval.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_manifest_aggregate(const ss_manifest *m, const ss_eval_row *rows, int n, double *mean, double *mean_sym,
                                int *count, ss_error *err) {
  const int NM = SS_EVAL_NMETHODS, cells = m->ngroups * 4 * NM;
  if (n < 0 || (n > 0 && !rows)) return ss_fail(err, SS_ERR_INVALID, "manifest table: bad rows");
  double *sum = calloc((size_t)cells * 2 + 1, sizeof(double));
  ss_eval_row *r = malloc(sizeof *r * (size_t)(n > 0 ? n : 1));
  if (!sum || !r) { free(sum), free(r); return ss_fail(err, SS_ERR_NOMEM, "manifest table: out of memory"); }
  if (n > 0) memcpy(r, rows, sizeof *r * (size_t)n);
  memset(count, 0, sizeof(int) * (size_t)cells);
  ss_status st = ss_eval_rows_canonical(r, &n, err); /* canonical order: any sharding sums the same */
  for (int i = 0; i < n && !st; i++) {
    const ss_eval_row *q = &r[i];
    if (q->x < 0 || q->y < 0 || q->x >= m->nmeshes || q->y >= m->nmeshes ||
        m->meshes[q->x].group != m->meshes[q->y].group || (unsigned)q->landmarks > 3 || (unsigned)q->method >= (unsigned)NM) {
      st = ss_fail(err, SS_ERR_INVALID, "results row %s,%s,%s,%d,%d is not a pair of this manifest (%d meshes)",
                   ss_pair_policy_name(q->policy), ss_lm_set_name(q->landmarks), ss_eval_method_name(q->method), q->x, q->y,
                   m->nmeshes);
      break;
    }
    int c = (m->meshes[q->x].group * 4 + q->landmarks) * NM + q->method;
    sum[c] += q->error, sum[cells + c] += q->error_sym, count[c]++;
  }
  for (int c = 0; c < cells; c++) {
    mean[c] = count[c] && !st ? sum[c] / count[c] : NAN;
    if (mean_sym) mean_sym[c] = count[c] && !st ? sum[cells + c] / count[c] : NAN;
  }
  free(sum), free(r);
  return st;
}
