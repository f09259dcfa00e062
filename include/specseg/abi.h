/* specseg — struct sizes for language bindings. Bindings that mirror public structs field by field
 * (python/specseg via ctypes) compare their mirror's size with the library's at load time, so a
 * header change fails loudly instead of corrupting memory. */
#ifndef SPECSEG_ABI_H
#define SPECSEG_ABI_H

#include <stddef.h>

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* sizeof the core library's public struct named e.g. "ss_mesh", "ss_segmentation"; 0 for an unknown
 * name. The render library's structs: ss_render_struct_size (render.h). */
SS_API size_t ss_struct_size(const char *name);

#ifdef __cplusplus
}
#endif
#endif
