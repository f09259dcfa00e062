/* ss_struct_size (specseg/abi.h): the name looked up in each module's table (abi/struct_sizes.h). It sits
 * above every module of the core library and includes none of their headers. */
#include "abi/struct_sizes.h"
#include "specseg/abi.h"

#include <string.h>

size_t ss_struct_size(const char *name) {
  static const ss_struct_size_entry *const tables[] = {ss_core_struct_sizes, ss_streamline_struct_sizes,
                                                       ss_segment_struct_sizes, ss_fmap_struct_sizes,
                                                       ss_match_struct_sizes};
  if (!name) return 0;
  for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++)
    for (const ss_struct_size_entry *e = tables[t]; e->name; e++)
      if (!strcmp(e->name, name)) return e->size;
  return 0;
}
