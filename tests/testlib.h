/* Minimal test harness: CHECK records failures and goes on; TEST_MAIN prints "N passed, N failed". */
#ifndef SS_TESTLIB_H
#define SS_TESTLIB_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int tl_pass = 0, tl_fail = 0, tl_skip = 0;

#define CHECK(cond)                                                                   \
  do {                                                                                \
    if (cond) tl_pass++;                                                              \
    else { tl_fail++; fprintf(stderr, "FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond); } \
  } while (0)

#define CHECK_MSG(cond, ...)                                                          \
  do {                                                                                \
    if (cond) tl_pass++;                                                              \
    else {                                                                            \
      tl_fail++;                                                                      \
      fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                 \
      fprintf(stderr, __VA_ARGS__);                                                   \
      fputc('\n', stderr);                                                            \
    }                                                                                 \
  } while (0)

#define CHECK_NEAR(a, b, tol) CHECK_MSG(fabs((double)(a) - (double)(b)) <= (tol), "%.17g vs %.17g (tol %g)", (double)(a), (double)(b), (double)(tol))

#define SKIP(...) do { tl_skip++; printf("SKIP: "); printf(__VA_ARGS__); printf("\n"); } while (0)

/* Data folder (../shared/data) or NULL when absent. */
static inline const char *tl_data_dir(void) {
  const char *d = getenv("SS_DATA_DIR");
  if (!d) return NULL;
  char probe[4096];
  snprintf(probe, sizeof probe, "%s/faust/tr_reg_000.off", d);
  FILE *f = fopen(probe, "rb");
  if (!f) return NULL;
  fclose(f);
  return d;
}

/* For each of nv vertices V (nv x 3), the vertex nearest to its mirror image in the plane x = 0 (brute
 * force: small test meshes); returns the largest of those distances. */
static inline double tl_mirror_map(const double *V, int nv, int *sym) {
  double maxd = 0;
  for (int i = 0; i < nv; i++) {
    const double *p = V + 3 * (size_t)i;
    double best = INFINITY;
    for (int j = 0; j < nv; j++) {
      const double *q = V + 3 * (size_t)j;
      const double d = (p[0] + q[0]) * (p[0] + q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
      if (d < best) best = d, sym[i] = j;
    }
    if (sqrt(best) > maxd) maxd = sqrt(best);
  }
  return maxd;
}

#define TEST_MAIN_END()                                                                  \
  do {                                                                                   \
    printf("%d passed, %d failed", tl_pass, tl_fail);                                    \
    if (tl_skip) printf(", %d skipped", tl_skip);                                        \
    printf("\n");                                                                        \
    /* 77: CTest's SKIP_RETURN_CODE, so a test that skipped checks shows as skipped */   \
    return tl_fail ? 1 : tl_skip ? 77 : 0;                                               \
  } while (0)

#endif
