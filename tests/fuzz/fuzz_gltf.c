/* libFuzzer harness: the glTF parser (.gltf JSON and .glb by the magic) on arbitrary bytes from memory
 * (no path: external buffers refused), as ss_read_mesh sees a file: a private copy with a trailing NUL.
 * Property: a valid mesh or an error "NAME:..." (fuzz_common.h); no crash, no sanitizer report, no hang. */
#include "fuzz_common.h"
#include "mesh/io_internal.h"

static ss_status parse(const char *name, const char *buf, size_t len, ss_mesh *m, ss_error *err) {
  return io_parse_gltf(NULL, name, buf, len, m, err);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fuzz_parser(parse, "fuzz.gltf", data, size);
  return 0;
}
