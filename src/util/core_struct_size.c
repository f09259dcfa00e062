/* sizeof of core.h's public structs that bindings mirror (ss_struct_size, specseg/abi.h). */
#include "abi/struct_sizes.h"
#include "specseg/core.h"

const ss_struct_size_entry ss_core_struct_sizes[] = {
    {"ss_mesh", sizeof(ss_mesh)},
    {"ss_error", sizeof(ss_error)},
    {"ss_sparse", sizeof(ss_sparse)},
    {NULL, 0},
};
