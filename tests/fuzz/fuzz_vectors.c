/* libFuzzer harness: the text vector readers (labels, maps, fields): ss_read_ints_memory,
 * ss_read_ints_lines_memory and ss_read_doubles_memory on the same bytes. Properties: they accept
 * and reject the same inputs as each other where they must (the two int readers agree exactly), line
 * numbers increase, and every error message starts with the input's name. */
#include "fuzz_common.h"
#include "specseg/io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  int *a = NULL, *b = NULL, *lines = NULL, na = -1, nb = -1, nd = -1;
  double *d = NULL;
  ss_error e1 = {{0}}, e2 = {{0}}, e3 = {{0}};
  ss_status s1 = ss_read_ints_memory(data, size, "<fuzz>", &a, &na, &e1);
  ss_status s2 = ss_read_ints_lines_memory(data, size, "<fuzz>", &b, &lines, &nb, &e2);
  ss_status s3 = ss_read_doubles_memory(data, size, "<fuzz>", &d, &nd, &e3);
  FUZZ_ASSERT(s1 == s2);
  if (s1) {
    FUZZ_ASSERT(a == NULL && b == NULL && lines == NULL);
    FUZZ_ASSERT(!strncmp(e1.msg, "<fuzz>", 6) && !strcmp(e1.msg, e2.msg));
  } else {
    FUZZ_ASSERT(a && b && lines && na == nb && na >= 0);
    FUZZ_ASSERT(!memcmp(a, b, sizeof(int) * (size_t)na));
    for (int i = 1; i < na; i++) FUZZ_ASSERT(lines[i] > lines[i - 1]);
    if (na > 0) FUZZ_ASSERT(lines[0] >= 1);
    /* every integer line is a number too */
    FUZZ_ASSERT(s3 == SS_OK && nd == na);
  }
  if (s3) FUZZ_ASSERT(d == NULL && !strncmp(e3.msg, "<fuzz>", 6));
  else FUZZ_ASSERT(d && nd >= 0);
  free(a), free(b), free(lines), free(d);
  return 0;
}
