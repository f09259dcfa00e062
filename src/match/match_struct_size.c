/* sizeof of match.h's public structs that bindings mirror (ss_struct_size, specseg/abi.h). */
#include "abi/struct_sizes.h"
#include "specseg/match.h"

const ss_struct_size_entry ss_match_struct_sizes[] = {
    {"ss_match_options", sizeof(ss_match_options)},
    {"ss_segment_pairs", sizeof(ss_segment_pairs)},
    {"ss_match_result", sizeof(ss_match_result)},
    {"ss_autopair_options", sizeof(ss_autopair_options)},
    {"ss_shape_prep", sizeof(ss_shape_prep)},
    {"ss_centre_signature", sizeof(ss_centre_signature)},
    {"ss_prepared_shape", sizeof(ss_prepared_shape)},
    {"ss_map_polish_options", sizeof(ss_map_polish_options)},
    {NULL, 0},
};
