/* The per-module tables behind ss_struct_size (specseg/abi.h): each module lists the sizes of its own
 * public structs that bindings mirror, in a file beside its code (e.g. segment/segment_struct_size.c);
 * abi/struct_size.c, above every module, looks a name up in them. This header includes nothing of the
 * library, so a module's table depends only on its own headers. */
#ifndef SPECSEG_ABI_STRUCT_SIZES_H
#define SPECSEG_ABI_STRUCT_SIZES_H

#include <stddef.h>

typedef struct ss_struct_size_entry {
  const char *name; /* "ss_mesh"; NULL ends a table */
  size_t size;
} ss_struct_size_entry;

extern const ss_struct_size_entry ss_core_struct_sizes[];       /* util/core_struct_size.c: core.h */
extern const ss_struct_size_entry ss_streamline_struct_sizes[]; /* streamline/streamline_struct_size.c */
extern const ss_struct_size_entry ss_segment_struct_sizes[];    /* segment/segment_struct_size.c */
extern const ss_struct_size_entry ss_fmap_struct_sizes[];       /* fmap/fmap_struct_size.c */
extern const ss_struct_size_entry ss_match_struct_sizes[];      /* match/match_struct_size.c */

#endif
