/* Pairing policies of paper §6.1: random pairs, same subject ("subj"), same pose ("pose"). */
#include "specseg/eval.h"

#include <stdlib.h>
#include <string.h>

static const char *const policy_names[3] = {"random", "subj", "pose"};

const char *ss_pair_policy_name(ss_pair_policy p) { return (unsigned)p < 3 ? policy_names[p] : "?"; }

int ss_pair_policy_parse(const char *s) {
  for (int i = 0; i < 3; i++)
    if (s && !strcmp(s, policy_names[i])) return i;
  return -1;
}

static int allowed(ss_pair_policy p, int nposes, int a, int b) {
  if (a == b) return 0;
  if (p == SS_POLICY_SUBJ) return a / nposes == b / nposes;
  if (p == SS_POLICY_POSE) return a % nposes == b % nposes;
  return 1;
}

ss_status ss_eval_pairs(ss_pair_policy policy, int nsubjects, int nposes, int npairs, uint64_t seed, int *x,
                        int *y, ss_error *err) {
  if ((unsigned)policy > 2) return ss_fail(err, SS_ERR_INVALID, "pairs: unknown policy %d", (int)policy);
  if (nsubjects < 1 || nposes < 1 || npairs < 0 || nsubjects > 10000 || nposes > 10000 ||
      (long)nsubjects * nposes > 46340)
    return ss_fail(err, SS_ERR_INVALID, "pairs: bad sizes (%d subjects, %d poses, %d pairs)", nsubjects, nposes,
                   npairs);
  if (npairs > 0 && (!x || !y)) return ss_fail(err, SS_ERR_INVALID, "pairs: NULL output");
  int ns = nsubjects * nposes;
  /* enumerate every allowed ordered pair, then a partial Fisher–Yates shuffle: sampling without
   * replacement, so no pair is evaluated twice */
  long total = 0;
  for (int a = 0; a < ns; a++)
    for (int b = 0; b < ns; b++) total += allowed(policy, nposes, a, b);
  if (total < npairs)
    return ss_fail(err, SS_ERR_INVALID, "pairs: policy %s allows only %ld pairs, %d requested",
                   ss_pair_policy_name(policy), total, npairs);
  if (npairs == 0) return SS_OK;
  int *all = malloc(sizeof(int) * (size_t)total);
  if (!all) return ss_fail(err, SS_ERR_NOMEM, "pairs: out of memory");
  long t = 0;
  for (int a = 0; a < ns; a++)
    for (int b = 0; b < ns; b++)
      if (allowed(policy, nposes, a, b)) all[t++] = a * ns + b;
  ss_rng r;
  /* one stream per policy, so adding a policy never changes another's pairs */
  ss_rng_seed(&r, seed ^ (0xA24BAED4963EE407ull * (uint64_t)(policy + 1)));
  for (int i = 0; i < npairs; i++) {
    int j = i + ss_rng_below(&r, (int)(total - i));
    int tmp = all[i];
    all[i] = all[j];
    all[j] = tmp;
    x[i] = all[i] / ns;
    y[i] = all[i] % ns;
  }
  free(all);
  return SS_OK;
}
