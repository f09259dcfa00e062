/* libFuzzer harness: the landmark file reader (ss_read_landmarks_memory). Properties: on success
 * n >= 1 non-negative indices on each side, ly = lx on one-column files, line numbers increasing;
 * on failure an error "<fuzz>:..." and nothing allocated. */
#include "fuzz_common.h"
#include "specseg/io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  int *lx = NULL, *ly = NULL, *lines = NULL, n = -1, cols = -1;
  ss_error e = {{0}};
  ss_status st = ss_read_landmarks_memory(data, size, "<fuzz>", &lx, &ly, &lines, &n, &cols, &e);
  if (st) {
    FUZZ_ASSERT(!strncmp(e.msg, "<fuzz>", 6));
  } else {
    FUZZ_ASSERT(n >= 1 && lx && ly && lines && (cols == 1 || cols == 2));
    for (int i = 0; i < n; i++) {
      FUZZ_ASSERT(lx[i] >= 0 && ly[i] >= 0);
      if (cols == 1) FUZZ_ASSERT(lx[i] == ly[i]);
      if (i) FUZZ_ASSERT(lines[i] > lines[i - 1]);
    }
  }
  free(lx), free(ly), free(lines);
  return 0;
}
