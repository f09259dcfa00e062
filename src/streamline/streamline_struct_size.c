/* sizeof of streamline.h's public structs that bindings mirror (ss_struct_size, specseg/abi.h). */
#include "abi/struct_sizes.h"
#include "specseg/streamline.h"

const ss_struct_size_entry ss_streamline_struct_sizes[] = {
    {"ss_cmcf_options", sizeof(ss_cmcf_options)},
    {"ss_remesh_options", sizeof(ss_remesh_options)},
    {NULL, 0},
};
