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

#define TEST_MAIN_END()                                                                  \
  do {                                                                                   \
    printf("%d passed, %d failed", tl_pass, tl_fail);                                    \
    if (tl_skip) printf(", %d skipped", tl_skip);                                        \
    printf("\n");                                                                        \
    /* 77: CTest's SKIP_RETURN_CODE, so a test that skipped checks shows as skipped */   \
    return tl_fail ? 1 : tl_skip ? 77 : 0;                                               \
  } while (0)

#endif
