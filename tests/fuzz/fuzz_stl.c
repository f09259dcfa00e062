/* libFuzzer harness: the STL parser (ascii and binary) on arbitrary bytes (as ss_read_mesh sees a
 * file: a private copy with a trailing NUL). Property: a valid mesh or an error "NAME:..." (fuzz_common.h); no crash,
 * no sanitizer report, no hang. */
#include "fuzz_common.h"
#include "mesh/io_internal.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char *buf = malloc(size + 1);
  if (!buf) return 0;
  memcpy(buf, data, size);
  buf[size] = '\0';
  ss_mesh m = {0};
  ss_error e = {{0}};
  ss_status st = io_parse_stl("fuzz.stl", buf, size, &m, &e);
  fuzz_check_mesh(st, &m, &e, "fuzz.stl");
  ss_mesh_free(&m);
  free(buf);
  return 0;
}
