/* libFuzzer harness: ss_read_mesh_memory (format by content sniffing, then the OFF / OBJ / PLY / STL /
 * glTF parser; nothing read from memory goes to assimp). Property: a valid mesh or an error
 * "<fuzz>:..." (fuzz_common.h); no crash, no sanitizer report (leaks included), no hang. */
#include "fuzz_common.h"
#include "specseg/io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  ss_mesh m;
  ss_error e = {{0}};
  ss_status st = ss_read_mesh_memory(data, size, "<fuzz>", &m, &e);
  fuzz_check_mesh(st, &m, &e, "<fuzz>");
  ss_mesh_free(&m);
  return 0;
}
