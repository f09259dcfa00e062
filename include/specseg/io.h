/* specseg — mesh and array file I/O. Readers never trust declared counts: they grow arrays as data
 * arrives, check every index, and report "PATH:LINE: what" (or "PATH: byte OFFSET: what") on error. */
#ifndef SPECSEG_IO_H
#define SPECSEG_IO_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Read OFF, OBJ or PLY (chosen by extension, case-insensitive; falls back to content sniffing).
 * OBJ polygons and OFF/PLY polygons are fan-triangulated; OBJ negative indices are relative.
 * OFF: optional [ST][C][N]OFF header, '#' comments, one vertex / one polygon a line, extra values
 * (colours, normals) ignored. PLY: ascii / binary LE / binary BE, x y z of any numeric type, faces
 * from the list `vertex_indices` (or `vertex_index`), everything else skipped. NaN/Inf coordinate
 * literals are read as such (ss_mesh_check reports them). Files without faces, polygons with fewer
 * than 3 vertices and out-of-range indices are errors (SS_ERR_PARSE). On failure *m is zeroed.
 *
 * Other formats go through the Open Asset Import Library (Debian's libassimp-dev, when the build found
 * it): STL (ascii and binary), glTF 2.0 (.gltf with embedded or external buffers, .glb), FBX, COLLADA
 * (.dae), 3DS and every other extension assimp supports; in memory, STL and glTF are recognised by
 * content. The scene is flattened: the meshes of every node, in depth-first order, with the node's
 * accumulated transform applied to their vertices (a mesh instanced twice appears twice); polygons are
 * triangulated, points and lines dropped; then vertices with exactly equal coordinates are welded
 * (O(n log n), by a sort; each kept vertex is the first of its group in the order the
 * scene lists them, for STL facet by facet), which joins STL's
 * per-facet vertex soup and the vertices other formats split at normal creases or texture seams into
 * one connected mesh. Coordinates are assimp's float32 values. Without assimp these files fail with
 * SS_ERR_UNSUPPORTED and a message naming libassimp-dev. Imports through assimp are serialised by a
 * process-wide lock (its error message is one global string); they are safe to call from any thread. */
SS_API ss_status ss_read_mesh(const char *path, ss_mesh *m, ss_error *err);
/* Does ss_read_mesh read files named like path by their extension? 1: OFF, OBJ or PLY (our readers);
 * 2: a format read through assimp (only when the library was built with it); 0: no. */
SS_API int ss_mesh_extension_supported(const char *path);
SS_API ss_status ss_read_off(const char *path, ss_mesh *m, ss_error *err);
SS_API ss_status ss_read_obj(const char *path, ss_mesh *m, ss_error *err);
SS_API ss_status ss_read_ply(const char *path, ss_mesh *m, ss_error *err);
/* The same from len bytes in memory (e.g. a program's standard input): the format always comes from
 * content sniffing (a "ply" first line, an OFF header or counts, OBJ keywords; with assimp also STL,
 * ascii or binary, glTF JSON and GLB); name (NULL:
 * "<memory>") stands for the file in messages, "NAME:LINE: what". buf is not modified or kept. */
SS_API ss_status ss_read_mesh_memory(const void *buf, size_t len, const char *name, ss_mesh *m, ss_error *err);
/* ss_read_mesh / ss_read_mesh_memory that also return the file's per-vertex colours: *rgb gets 3*nv
 * malloc'd bytes (free them) when the file has them, else NULL (rgb NULL: not wanted, as ss_read_mesh).
 * PLY: vertex properties red, green, blue (or diffuse_red.., or r g b; integer types clamped to
 * 0..255, floating-point ones in [0, 1] scaled by 255); other formats give NULL. */
SS_API ss_status ss_read_mesh_colors(const char *path, ss_mesh *m, unsigned char **rgb, ss_error *err);
SS_API ss_status ss_read_mesh_colors_memory(const void *buf, size_t len, const char *name, ss_mesh *m,
                                            unsigned char **rgb, ss_error *err);

/* Write by extension (.off, .ply or .obj; .ply is binary little-endian). rgb: NULL or 3*nv bytes of
 * per-vertex colour (OFF becomes COFF with "x y z r g b 255" lines; PLY gets uchar red green blue; OBJ
 * "v x y z r g b" with colours in [0, 1]; OBJ faces are 1-based "f a b c").
 * Coordinates are written losslessly (%.17g text, float64 binary): write -> read is exact. */
SS_API ss_status ss_write_mesh(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_error *err);
SS_API ss_status ss_write_off(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_error *err);
typedef enum ss_ply_format { SS_PLY_ASCII = 0, SS_PLY_BINARY_LE = 1, SS_PLY_BINARY_BE = 2 } ss_ply_format;
SS_API ss_status ss_write_ply(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_ply_format fmt,
                              ss_error *err);
SS_API ss_status ss_write_obj(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_error *err);
/* PLY with an integer vertex property `label` (labels: nv values, e.g. segment ids; NULL: none) after
 * the colours; ss_write_mesh_labels: the same for .ply, ss_write_mesh (labels dropped) otherwise. */
SS_API ss_status ss_write_ply_labels(const char *path, const ss_mesh *m, const unsigned char *rgb, const int *labels,
                                     ss_ply_format fmt, ss_error *err);
SS_API ss_status ss_write_mesh_labels(const char *path, const ss_mesh *m, const unsigned char *rgb, const int *labels,
                                      ss_error *err);

/* NumPy .npy (format 1.0, '<f8', C order) of a rows x cols matrix given column-major in `a`. */
SS_API ss_status ss_write_npy(const char *path, const double *a, int rows, int cols, ss_error *err);
/* Reads '<f8' or '>f8', C or Fortran order, 1-D or 2-D; returns a freshly malloc'd column-major array. */
SS_API ss_status ss_read_npy(const char *path, double **a, int *rows, int *cols, ss_error *err);
/* Integers: writes '<i4'; reads '<i4', '<i8' (or big-endian '>i4', '>i8'; int64 values must fit an int),
 * C or Fortran order, 1-D (rows = n, cols = 1) or 2-D, into a malloc'd column-major int array. */
SS_API ss_status ss_write_npy_ints(const char *path, const int *a, int rows, int cols, ss_error *err);
SS_API ss_status ss_read_npy_ints(const char *path, int **a, int *rows, int *cols, ss_error *err);
/* ss_read_npy / ss_read_npy_ints of len bytes in memory; name (NULL: "<memory>") stands for the file. */
SS_API ss_status ss_read_npy_memory(const void *buf, size_t len, const char *name, double **a, int *rows, int *cols,
                                    ss_error *err);
SS_API ss_status ss_read_npy_ints_memory(const void *buf, size_t len, const char *name, int **a, int *rows, int *cols,
                                         ss_error *err);

/* Text vectors: one value a line. Integers (labels, maps, landmark indices) and doubles (%.17g;
 * "inf" allowed). Readers allocate *out with malloc and set *n; comments (#) and blank lines skipped.
 * A line with two values, a non-number or an int out of range is an error "PATH:LINE: what". */
SS_API ss_status ss_read_ints(const char *path, int **out, int *n, ss_error *err);
SS_API ss_status ss_write_ints(const char *path, const int *v, int n, ss_error *err);
SS_API ss_status ss_read_doubles(const char *path, double **out, int *n, ss_error *err);
SS_API ss_status ss_write_doubles(const char *path, const double *v, int n, ss_error *err);
/* ss_read_ints / ss_read_doubles of len bytes in memory; name (NULL: "<memory>") as PATH in messages. */
SS_API ss_status ss_read_ints_memory(const void *buf, size_t len, const char *name, int **out, int *n, ss_error *err);
SS_API ss_status ss_read_doubles_memory(const void *buf, size_t len, const char *name, double **out, int *n,
                                        ss_error *err);
/* ss_read_ints with *lines: the n malloc'd 1-based line numbers of the values (comments and blank
 * lines skipped), so a caller that checks the values (a map against its target mesh) can say
 * "PATH:LINE: ..."; and the same of len bytes in memory (name NULL: "<memory>"). */
SS_API ss_status ss_read_ints_lines(const char *path, int **out, int **lines, int *n, ss_error *err);
SS_API ss_status ss_read_ints_lines_memory(const void *buf, size_t len, const char *name, int **out, int **lines, int *n,
                                           ss_error *err);
/* Landmark file: one landmark a line, "i" (same vertex on both shapes) or "i j" (i on the first shape,
 * j on the second); '#' comments and blank lines skipped. *lx, *ly: n malloc'd vertex indices (ly =
 * lx on one-column lines). columns (may be NULL): 2 when any line has two indices, else 1. Errors
 * "PATH:LINE: what" (negative or non-integer index, three values); an empty file is SS_ERR_PARSE. */
SS_API ss_status ss_read_landmarks(const char *path, int **lx, int **ly, int *n, int *columns, ss_error *err);
/* The same, with *lines (NULL: not wanted): the n malloc'd 1-based line numbers of the landmarks, so a
 * caller that checks them against its meshes can say "PATH:LINE: ..." too. */
SS_API ss_status ss_read_landmarks_lines(const char *path, int **lx, int **ly, int **lines, int *n, int *columns,
                                         ss_error *err);
/* ss_read_landmarks_lines of len bytes in memory; name (NULL: "<memory>") as PATH in messages. */
SS_API ss_status ss_read_landmarks_memory(const void *buf, size_t len, const char *name, int **lx, int **ly,
                                          int **lines, int *n, int *columns, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
