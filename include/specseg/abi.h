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

/* sizeof of one of the core library's public structs, by name, so that a binding that mirrors the
 * struct field by field can compare its mirror's size at load time.
 *
 * Inputs:
 *   name     the struct's name, e.g. "ss_mesh", "ss_segmentation" (NULL allowed)
 * Returns: its size in bytes; 0 for NULL or an unknown name. The render library's structs:
 *   ss_render_struct_size (render.h).
 */
SS_API size_t ss_struct_size(const char *name);

#ifdef __cplusplus
}
#endif
#endif
