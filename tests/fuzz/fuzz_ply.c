/* libFuzzer harness: the PLY parser on arbitrary bytes (as ss_read_ply sees a file: a private
 * copy with a trailing NUL). Property: a valid mesh or an error "NAME:..." (fuzz_common.h); no crash,
 * no sanitizer report, no hang. */
#include "fuzz_common.h"
#include "mesh/io_internal.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fuzz_parser(io_parse_ply, "fuzz.ply", data, size);
  return 0;
}
