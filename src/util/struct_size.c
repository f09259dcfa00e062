/* sizeof of the core library's public structs that bindings mirror (see specseg/abi.h). */
#include "specseg/abi.h"
#include "specseg/geodesic.h"
#include "specseg/match.h"
#include "specseg/segment.h"
#include "specseg/streamline.h"

#include <string.h>

size_t ss_struct_size(const char *name) {
  static const struct {
    const char *name;
    size_t size;
  } T[] = {
      {"ss_mesh", sizeof(ss_mesh)},
      {"ss_error", sizeof(ss_error)},
      {"ss_sparse", sizeof(ss_sparse)},
      {"ss_cmcf_options", sizeof(ss_cmcf_options)},
      {"ss_remesh_options", sizeof(ss_remesh_options)},
      {"ss_segment_options", sizeof(ss_segment_options)},
      {"ss_segmentation", sizeof(ss_segmentation)},
      {"ss_fmap_match_options", sizeof(ss_fmap_match_options)},
      {"ss_match_options", sizeof(ss_match_options)},
      {"ss_segment_pairs", sizeof(ss_segment_pairs)},
      {"ss_match_result", sizeof(ss_match_result)},
      {"ss_autopair_options", sizeof(ss_autopair_options)},
      {"ss_shape_prep", sizeof(ss_shape_prep)},
      {"ss_centre_signature", sizeof(ss_centre_signature)},
      {"ss_prepared_shape", sizeof(ss_prepared_shape)},
  };
  if (!name) return 0;
  for (size_t i = 0; i < sizeof T / sizeof T[0]; i++)
    if (!strcmp(T[i].name, name)) return T[i].size;
  return 0;
}
