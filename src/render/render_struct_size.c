/* sizeof of the render library's public structs that bindings mirror (see specseg/abi.h). */
#include "specseg/render.h"

#include <string.h>

size_t ss_render_struct_size(const char *name) {
  if (!name) return 0;
  if (!strcmp(name, "ss_render_options")) return sizeof(ss_render_options);
  if (!strcmp(name, "ss_render_scene")) return sizeof(ss_render_scene);
  return 0;
}
