/* sizeof of fmap.h's public structs that bindings mirror (ss_struct_size, specseg/abi.h). */
#include "abi/struct_sizes.h"
#include "specseg/fmap.h"

const ss_struct_size_entry ss_fmap_struct_sizes[] = {
    {"ss_fmap_match_options", sizeof(ss_fmap_match_options)},
    {NULL, 0},
};
