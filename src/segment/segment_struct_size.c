/* sizeof of segment.h's public structs that bindings mirror (ss_struct_size, specseg/abi.h). */
#include "abi/struct_sizes.h"
#include "specseg/segment.h"

const ss_struct_size_entry ss_segment_struct_sizes[] = {
    {"ss_segment_options", sizeof(ss_segment_options)},
    {"ss_segmentation", sizeof(ss_segmentation)},
    {NULL, 0},
};
