/* The range checks of the sanitizer-aware kernels (util/asan_region.h): in a sanitizer build a range
 * that is addressable passes, and one that runs one double past its block, or starts misaligned, is
 * reported by the sanitizers as any bad access would be (CTest runs this program with the argument
 * "past" and "misaligned" and looks for the report). Outside a sanitizer build there is nothing to
 * check (SKIP). */
#include "util/asan_region.h"
#include "testlib.h"

#include <string.h>

int main(int argc, char **argv) {
#ifndef SSI_ASAN
  (void)argc, (void)argv;
  SKIP("not a sanitizer build: the range checks are compiled out");
#else
  double *a = malloc(sizeof(double) * 16);
  CHECK(a != NULL);
  if (a) {
    for (int i = 0; i < 16; i++) a[i] = i;
    if (argc > 1 && !strcmp(argv[1], "past")) ssi_checked_doubles(a + 1, 16); /* one past the block */
    if (argc > 1 && !strcmp(argv[1], "misaligned")) ssi_checked_doubles((const double *)((const char *)a + 4), 2);
    ssi_checked_doubles(a, 16), ssi_checked_doubles(a + 15, 1), ssi_checked_doubles(a + 16, 0);
    ssi_checked_ints((const int *)a, 32), ssi_checked_object(a);
    CHECK(a[15] == 15); /* (reached only when nothing was reported) */
  }
  free(a);
#endif
  TEST_MAIN_END();
}
