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
/* STL, ASCII or binary (read_stl.c); the facets' corners welded by exact coordinates. */
ss_status io_parse_stl(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err);
/* Is this STL by content? Binary: the length is exactly 84 + 50 n for the n > 0 facets its header
 * declares; ASCII: the word "solid" first, then "facet" (or "FACET") within the first 4 KiB. */
int io_stl_sniff(const char *buf, size_t len);

/* glTF 2.0, .gltf (JSON) or .glb (binary container) by the magic (read_gltf.c): the triangles of every mesh
 * instance of the scene, node transforms applied, welded by exact coordinates. path: the .gltf's own path,
 * to find external buffer files beside it; NULL (from memory) refuses them. name for messages (NULL: path or
 * "<memory>"). */
ss_status io_parse_gltf(const char *path, const char *name, const char *buf, size_t len, ss_mesh *m, ss_error *err);
/* Is this glTF by content? The GLB magic "glTF", or text whose first non-blank is '{' with the key "asset"
 * within the first 64 KiB. */
int io_gltf_sniff(const char *buf, size_t len);

/* Read the whole file and run one of the parsers above on it (the body of ss_read_off/obj/ply). */
typedef ss_status (*io_mesh_parser)(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err);
ss_status io_read_with(const char *path, io_mesh_parser parse, ss_mesh *m, ss_error *err);

/* The format of our own readers that path's extension names (case-insensitive): 'o' OFF, 'j' OBJ, 'p' PLY,
 * 's' STL, 'g' glTF / GLB; 0: none of ours (path NULL included). */
int ssi_mesh_own_format(const char *path);

/* ---- formats read through assimp (read_assimp.c), by extension only ----
 * Does the extension of path belong to a format read through assimp (FBX, COLLADA, ...; never OFF, OBJ,
 * PLY, STL, glTF or GLB)? Then 1, and the lower-case extension in hint (cap bytes) when hint is not NULL.
 * Without assimp in the build, the common formats' extensions still answer 1 (ssi_read_assimp then
 * refuses). */
int ssi_mesh_assimp_ext(const char *path, char *hint, size_t cap);
/* Read a scene through assimp, by path (path not NULL: a regular file) or from len bytes in buf with
 * the format hint ("fbx", "dae", ...); name for messages. All node meshes merged with their transforms,
 * triangles only, vertices welded exactly (ssi_mesh_weld). Without assimp: SS_ERR_UNSUPPORTED naming
 * libassimp-dev. */
ss_status ssi_read_assimp(const char *path, const char *name, const char *buf, size_t len, const char *hint, ss_mesh *m,
                          ss_error *err);
/* Merge vertices with exactly equal coordinates (-0 = 0; NaN never merged), O(n log n) by a sort: the
 * vertices keep the order of their first occurrence, faces are renumbered (a face may become
 * degenerate; none is removed). *merged (may be NULL): vertices removed. */
ss_status ssi_mesh_weld(ss_mesh *m, int *merged, ss_error *err);

/* Moves grown arrays into a mesh (shrinks to fit; frees the vectors). */
ss_status io_finish_mesh(io_dvec *V, io_ivec *F, ss_mesh *m, const char *path, ss_error *err);

#endif
