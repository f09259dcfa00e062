/* Internal to the mesh readers: the per-format parsers over a loaded buffer. Not public API. */
#ifndef SS_IO_INTERNAL_H
#define SS_IO_INTERNAL_H

#include <stdint.h>

#include "specseg/core.h"
#include "util/io_text.h"

/* Largest vertex / face count any reader accepts (3*n must fit an int for index arithmetic). */
#define IO_MAX_ELEMENTS (INT32_MAX / 3)

/* Parsers over an already loaded buffer (path only for messages). On success *m owns the data.
 * Meshes without faces are rejected: everything downstream needs triangles. */
ss_status io_parse_off(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err);
ss_status io_parse_obj(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err);
ss_status io_parse_ply(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err);
/* The same with the vertices' colours (red / green / blue, also diffuse_red.. or r g b): *rgb gets 3 nv
 * malloc'd bytes, or NULL when the file has none (rgb itself may be NULL: not wanted). */
ss_status io_parse_ply_rgb(const char *path, const char *buf, size_t len, ss_mesh *m, unsigned char **rgb,
                           ss_error *err);

/* Read the whole file and run one of the parsers above on it (the body of ss_read_off/obj/ply). */
typedef ss_status (*io_mesh_parser)(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err);
ss_status io_read_with(const char *path, io_mesh_parser parse, ss_mesh *m, ss_error *err);

/* Moves grown arrays into a mesh (shrinks to fit; frees the vectors). */
ss_status io_finish_mesh(io_dvec *V, io_ivec *F, ss_mesh *m, const char *path, ss_error *err);

#endif
