/* libFuzzer harness: ss_read_mesh_memory (format by content sniffing, then the OFF / OBJ / PLY / STL
 * parser, or assimp for glTF / GLB). Property: a valid mesh or an error "<fuzz>:..." (fuzz_common.h).
 *
 * assimp's importers throw out of malformed input and leak the objects they made (its ASCII STL
 * reader three times, its GLB reader once, in four fuzz runs; STL is now our own reader). Those leaks
 * are assimp's and out of our reach, so for inputs that may go to assimp (ssi_mesh_assimp_sniff)
 * LeakSanitizer does not count what the call allocates. Everything else still holds for them: ASan's
 * overflows and use-after-free, UBSan, the result's properties. Our flattening of an assimp scene is
 * leak-checked by test_read_assimp (valid and malformed files). */
#include "fuzz_common.h"
#include "mesh/io_internal.h"
#include "specseg/io.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FUZZ_LSAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) && !defined(FUZZ_LSAN)
#define FUZZ_LSAN 1
#endif
#ifdef FUZZ_LSAN
#include <sanitizer/lsan_interface.h>
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  ss_mesh m;
  ss_error e = {{0}};
  const int to_assimp = ssi_mesh_assimp_sniff((const char *)data, size) != NULL;
#ifdef FUZZ_LSAN
  if (to_assimp) __lsan_disable();
#else
  (void)to_assimp;
#endif
  ss_status st = ss_read_mesh_memory(data, size, "<fuzz>", &m, &e);
#ifdef FUZZ_LSAN
  if (to_assimp) __lsan_enable();
#endif
  fuzz_check_mesh(st, &m, &e, "<fuzz>");
  ss_mesh_free(&m);
  return 0;
}
