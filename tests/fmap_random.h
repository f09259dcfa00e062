/* Random functional-map probes for tests and benchmarks of the dense solver (test_fmap_work,
 * bench_fmap_work): the solver's cost and its bit-level behaviour depend on the sizes alone, not on
 * where the probes come from. */
#ifndef SS_TESTS_FMAP_RANDOM_H
#define SS_TESTS_FMAP_RANDOM_H

#include "specseg/fmap.h"

#include <stdlib.h>

/* uniform in [-1, 1), from the linear congruential state *s */
static inline double fr_urand(unsigned *s) {
  *s = *s * 1664525u + 1013904223u;
  return (*s >> 8) / 8388608.0 - 1.0;
}

/* k-sized probes, every entry uniform in [-1, 1): p descriptors (A), the first nd with packed
 * symmetric operators (P), no orientation operators (O); free with ss_fmap_probes_free. P and O get
 * at least one block so that a count of 0 still leaves them allocated. */
static inline void fr_random_probes(int k, int p, int nd, int no, unsigned *s, ss_fmap_probes *P) {
  const size_t kk = (size_t)k * (k + 1) / 2;
  P->k = k, P->p = p, P->nd = nd, P->no = no;
  P->A = malloc(sizeof(double) * (size_t)k * p);
  P->P = malloc(sizeof(double) * kk * (nd ? nd : 1));
  P->O = malloc(sizeof(double) * (size_t)k * k * (no ? no : 1));
  for (size_t i = 0; i < (size_t)k * p; i++) P->A[i] = fr_urand(s);
  for (size_t i = 0; i < kk * nd; i++) P->P[i] = fr_urand(s);
  for (size_t i = 0; i < (size_t)k * k * no; i++) P->O[i] = fr_urand(s);
}

#endif
