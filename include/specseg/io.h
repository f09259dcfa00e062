/* specseg — mesh and array file I/O. Readers never trust declared counts: they grow arrays as data
 * arrives, check every index, and report "PATH:LINE: what" (or "PATH: byte OFFSET: what") on error. */
#ifndef SPECSEG_IO_H
#define SPECSEG_IO_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Reads a triangle mesh from a file, the format chosen by extension (case-insensitive; content
 * sniffing when the extension says nothing).
 * OFF, OBJ, PLY, STL and glTF 2.0 are read by our own readers: polygons are fan-triangulated; OBJ negative
 * indices are relative. OFF: optional [ST][C][N]OFF header, '#' comments, one vertex / one polygon a
 * line, extra values (colours, normals) ignored. PLY: ascii / binary LE / binary BE, x y z of any
 * numeric type, faces from the list `vertex_indices` (or `vertex_index`), everything else skipped.
 * STL: binary (exactly 84 + 50 n bytes for the n facets its header declares; float32 corners) or
 * ascii ("solid", facets of three "vertex" lines, "endsolid"; keywords in either case; several solids
 * allowed; facet normals checked as numbers and ignored). NaN/Inf coordinate literals are read as such
 * (ss_mesh_check reports them). glTF: see ss_read_gltf.
 * Other formats, by extension only, go through the Open Asset Import Library (Debian's libassimp-dev,
 * when the build found it): FBX, COLLADA (.dae), 3DS and every other extension assimp supports. The
 * scene is flattened: the meshes of every node, in depth-first order, with the node's accumulated
 * transform applied to their vertices (a mesh instanced twice appears twice); polygons are
 * triangulated, points and lines dropped; coordinates are assimp's float32 values. Imports through
 * assimp are serialised by a process-wide lock (its error message is one global string); they are
 * safe to call from any thread.
 * An STL's and a scene's vertices with exactly equal coordinates are then welded (O(n log n), by a
 * sort; each kept vertex is the first of its group in file order, for STL facet by facet), which joins
 * an STL's per-facet vertex soup, and the vertices other formats split at normal creases or texture
 * seams, into one connected mesh.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 * Errors: SS_ERR_IO (cannot open or read the file); SS_ERR_PARSE "PATH:LINE: what" (malformed
 *   content, no faces, a polygon of fewer than 3 vertices, an index out of range, unknown format);
 *   SS_ERR_UNSUPPORTED (an assimp format in a build without assimp: the message names libassimp-dev;
 *   glTF refusals, see ss_read_gltf);
 *   SS_ERR_INVALID on NULL arguments; SS_ERR_NOMEM. On failure *m is zeroed.
 */
SS_API ss_status ss_read_mesh(const char *path, ss_mesh *m, ss_error *err);
/* Does ss_read_mesh read files named like path by their extension?
 *
 * Inputs:
 *   path     a file name (NULL allowed)
 * Returns: 1 for OFF, OBJ, PLY, STL, glTF or GLB (our readers); 2 for a format read through assimp
 *   (only when the library was built with it); 0 otherwise.
 */
SS_API int ss_mesh_extension_supported(const char *path);
/* Reads an OFF file (the OFF reader of ss_read_mesh, whatever the extension).
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 * Errors: SS_ERR_IO; SS_ERR_PARSE "PATH:LINE: what"; SS_ERR_NOMEM. On failure *m is zeroed.
 */
SS_API ss_status ss_read_off(const char *path, ss_mesh *m, ss_error *err);
/* Reads a Wavefront OBJ file (the OBJ reader of ss_read_mesh, whatever the extension).
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 * Errors: SS_ERR_IO; SS_ERR_PARSE "PATH:LINE: what"; SS_ERR_NOMEM. On failure *m is zeroed.
 */
SS_API ss_status ss_read_obj(const char *path, ss_mesh *m, ss_error *err);
/* Reads a PLY file, ascii or binary (the PLY reader of ss_read_mesh, whatever the extension).
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 * Errors: SS_ERR_IO; SS_ERR_PARSE "PATH: what" with the line or byte offset; SS_ERR_NOMEM. On failure
 *   *m is zeroed.
 */
SS_API ss_status ss_read_ply(const char *path, ss_mesh *m, ss_error *err);
/* Reads an STL file, ascii or binary (the STL reader of ss_read_mesh, whatever the extension): the
 * facets' corners welded by exact coordinates into one mesh.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 * Errors: SS_ERR_IO; SS_ERR_PARSE "PATH:LINE: what" (ascii) or "PATH: what" (binary, e.g. a length
 *   that is not 84 + 50 n for the n facets its header declares); SS_ERR_NOMEM. On failure *m is zeroed.
 */
SS_API ss_status ss_read_stl(const char *path, ss_mesh *m, ss_error *err);
/* Reads a glTF 2.0 file, .gltf (JSON) or .glb (binary), told apart by content (the glTF reader of
 * ss_read_mesh, whatever the extension). Buffers: base64 data URIs, the GLB's BIN chunk, or files
 * named by a relative (or absolute) path, found beside the .gltf (other URI schemes are refused). The
 * scene `scene` (else the first; without scenes every mesh once, untransformed) is flattened: the
 * triangles of every mesh instance (modes TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN; points and lines
 * dropped), in depth-first node order, with the node's world transform (matrix or translation /
 * rotation / scale) applied in double precision; vertices with exactly equal coordinates are welded
 * as for STL. Positions float32, or integers with KHR_mesh_quantization; indices 8, 16 or 32 bit.
 * Refused: glTF 1.0, other required extensions (Draco, meshopt, ...), sparse accessors, accessors
 * without a buffer view, node cycles, and a scene that places its stored vertices (each POSITION
 * accessor once) more than 64 times over once past 2^20 vertices (instancing out of proportion to
 * the file: a few kilobytes could otherwise ask for many GB).
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 * Errors: SS_ERR_IO (the file or an external buffer cannot be read); SS_ERR_PARSE "PATH: what" naming
 *   the element (e.g. "accessors[2]: count 9 with stride 12 needs 108 bytes; bufferViews[0] has 96";
 *   JSON syntax: "PATH:LINE:COLUMN: what"); SS_ERR_UNSUPPORTED (glTF 1.0, a required extension, a
 *   sparse accessor or one without bufferView, a URI scheme other than data:, an external buffer
 *   when read from memory); SS_ERR_INVALID on NULL arguments; SS_ERR_NOMEM.
 *   On failure *m is zeroed.
 */
SS_API ss_status ss_read_gltf(const char *path, ss_mesh *m, ss_error *err);
/* ss_read_mesh from len bytes in memory (e.g. a program's standard input). The format always comes
 * from content sniffing: STL (ascii or binary), a "ply" first line, an OFF header or counts, OBJ
 * keywords, glTF JSON (a '{' first, the key "asset" within 64 KiB) or GLB (the magic "glTF"). A glTF
 * read from memory can only use embedded buffers (data URIs, the GLB's BIN chunk).
 *
 * Inputs:
 *   buf, len the bytes (not modified or kept; buf may be NULL when len is 0)
 *   name     stands for the file in messages, "NAME:LINE: what" (NULL: "<memory>")
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 * Errors: as ss_read_mesh (SS_ERR_INVALID also for a NULL buffer with len > 0).
 */
SS_API ss_status ss_read_mesh_memory(const void *buf, size_t len, const char *name, ss_mesh *m, ss_error *err);
/* ss_read_mesh that also returns the file's per-vertex colours. PLY: vertex properties red, green,
 * blue (or diffuse_red.., or r g b; integer types clamped to 0..255, floating-point ones in [0, 1]
 * scaled by 255); other formats give no colours.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 *   rgb      (NULL: not wanted) *rgb gets 3*nv malloc'd bytes (free()) when the file has colours,
 *            else NULL
 * Errors: as ss_read_mesh.
 */
SS_API ss_status ss_read_mesh_colors(const char *path, ss_mesh *m, unsigned char **rgb, ss_error *err);
/* ss_read_mesh_colors from len bytes in memory, the format from content sniffing as
 * ss_read_mesh_memory.
 *
 * Inputs:
 *   buf, len the bytes (not modified or kept)
 *   name     stands for the file in messages (NULL: "<memory>")
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 *   rgb      as ss_read_mesh_colors
 * Errors: as ss_read_mesh_memory.
 */
SS_API ss_status ss_read_mesh_colors_memory(const void *buf, size_t len, const char *name, ss_mesh *m,
                                            unsigned char **rgb, ss_error *err);

/* Writes a mesh, the format chosen by the extension: .off, .ply (binary little-endian) or .obj
 * (case-insensitive). Coordinates are written losslessly (%.17g text, float64 binary): write -> read
 * is exact.
 *
 * Inputs:
 *   path     the file (written through a temporary file renamed into place)
 *   m        the mesh
 *   rgb      NULL or 3*nv bytes of per-vertex colour (OFF becomes COFF with "x y z r g b 255" lines;
 *            PLY gets uchar red green blue; OBJ "v x y z r g b" with colours in [0, 1])
 * Errors: SS_ERR_INVALID on bad sizes, missing arrays or a face index out of range; SS_ERR_IO when
 *   the file cannot be written. SS_ERR_UNSUPPORTED for another extension.
 */
SS_API ss_status ss_write_mesh(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_error *err);
/* Writes an OFF file (COFF with "x y z r g b 255" lines when rgb is given), coordinates %.17g.
 *
 * Inputs:
 *   path     the file
 *   m        the mesh
 *   rgb      NULL or 3*nv bytes of per-vertex colour
 * Errors: SS_ERR_INVALID on bad sizes, missing arrays or a face index out of range; SS_ERR_IO when
 *   the file cannot be written.
 */
SS_API ss_status ss_write_off(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_error *err);
typedef enum ss_ply_format { SS_PLY_ASCII = 0, SS_PLY_BINARY_LE = 1, SS_PLY_BINARY_BE = 2 } ss_ply_format;
/* Writes a PLY file in the given encoding (float64 coordinates, int faces; uchar red green blue
 * when rgb is given).
 *
 * Inputs:
 *   path     the file
 *   m        the mesh
 *   rgb      NULL or 3*nv bytes of per-vertex colour
 *   fmt      SS_PLY_ASCII, SS_PLY_BINARY_LE or SS_PLY_BINARY_BE
 * Errors: SS_ERR_INVALID on bad sizes, missing arrays or a face index out of range; SS_ERR_IO when
 *   the file cannot be written. SS_ERR_INVALID also for an unknown fmt.
 */
SS_API ss_status ss_write_ply(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_ply_format fmt,
                              ss_error *err);
/* Writes an OBJ file: "v x y z" (with rgb: "v x y z r g b", colours in [0, 1]) and 1-based
 * "f a b c" lines, coordinates %.17g.
 *
 * Inputs:
 *   path     the file
 *   m        the mesh
 *   rgb      NULL or 3*nv bytes of per-vertex colour
 * Errors: SS_ERR_INVALID on bad sizes, missing arrays or a face index out of range; SS_ERR_IO when
 *   the file cannot be written.
 */
SS_API ss_status ss_write_obj(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_error *err);
/* Writes a PLY file with an integer vertex property `label` after the colours (e.g. segment ids).
 *
 * Inputs:
 *   path, m, rgb, fmt  as ss_write_ply
 *   labels   nv integers (NULL: no label property)
 * Errors: SS_ERR_INVALID on bad sizes, missing arrays or a face index out of range; SS_ERR_IO when
 *   the file cannot be written. SS_ERR_INVALID also for an unknown fmt.
 */
SS_API ss_status ss_write_ply_labels(const char *path, const ss_mesh *m, const unsigned char *rgb, const int *labels,
                                     ss_ply_format fmt, ss_error *err);
/* ss_write_ply_labels (binary little-endian) for a .ply path, ss_write_mesh (labels dropped)
 * otherwise.
 *
 * Inputs:
 *   path, m, rgb  as ss_write_mesh
 *   labels   nv integers (NULL: none)
 * Errors: as ss_write_mesh / ss_write_ply_labels.
 */
SS_API ss_status ss_write_mesh_labels(const char *path, const ss_mesh *m, const unsigned char *rgb, const int *labels,
                                      ss_error *err);

/* Writes a NumPy .npy file (format 1.0, '<f8', C order) of a rows x cols matrix.
 *
 * Inputs:
 *   path     the file
 *   a        rows x cols doubles, column-major
 *   rows, cols  the shape (>= 0)
 * Errors: SS_ERR_INVALID on a negative shape or a NULL array; SS_ERR_IO when the file cannot be
 *   written.
 */
SS_API ss_status ss_write_npy(const char *path, const double *a, int rows, int cols, ss_error *err);
/* Reads a NumPy .npy file of doubles: '<f8' or '>f8', C or Fortran order, 1-D (rows = n,
 * cols = 1) or 2-D.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   a        *a: a malloc'd rows x cols column-major array (free())
 *   rows, cols  the shape
 * Errors: SS_ERR_IO (cannot open or read the file); SS_ERR_PARSE (not a .npy, another dtype, more than
 *   2 dimensions, a truncated file, or for ints a value that does not fit an int); SS_ERR_NOMEM.
 */
SS_API ss_status ss_read_npy(const char *path, double **a, int *rows, int *cols, ss_error *err);
/* Writes a NumPy .npy file of integers ('<i4', C order) of a rows x cols matrix.
 *
 * Inputs:
 *   path     the file
 *   a        rows x cols ints, column-major
 *   rows, cols  the shape (>= 0)
 * Errors: SS_ERR_INVALID on a negative shape or a NULL array; SS_ERR_IO when the file cannot be
 *   written.
 */
SS_API ss_status ss_write_npy_ints(const char *path, const int *a, int rows, int cols, ss_error *err);
/* Reads a NumPy .npy file of integers: '<i4', '<i8' (or big-endian '>i4', '>i8'; int64 values must
 * fit an int), C or Fortran order, 1-D (rows = n, cols = 1) or 2-D.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   a        *a: a malloc'd rows x cols column-major int array (free())
 *   rows, cols  the shape
 * Errors: SS_ERR_IO (cannot open or read the file); SS_ERR_PARSE (not a .npy, another dtype, more than
 *   2 dimensions, a truncated file, or for ints a value that does not fit an int); SS_ERR_NOMEM.
 */
SS_API ss_status ss_read_npy_ints(const char *path, int **a, int *rows, int *cols, ss_error *err);
/* ss_read_npy of len bytes in memory.
 *
 * Inputs:
 *   buf, len the bytes (not kept)
 *   name     stands for the file in messages (NULL: "<memory>")
 * Outputs:
 *   a, rows, cols  as ss_read_npy
 * Errors: as ss_read_npy; SS_ERR_INVALID for a NULL buffer with len > 0.
 */
SS_API ss_status ss_read_npy_memory(const void *buf, size_t len, const char *name, double **a, int *rows, int *cols,
                                    ss_error *err);
/* ss_read_npy_ints of len bytes in memory.
 *
 * Inputs:
 *   buf, len the bytes (not kept)
 *   name     stands for the file in messages (NULL: "<memory>")
 * Outputs:
 *   a, rows, cols  as ss_read_npy_ints
 * Errors: as ss_read_npy_ints; SS_ERR_INVALID for a NULL buffer with len > 0.
 */
SS_API ss_status ss_read_npy_ints_memory(const void *buf, size_t len, const char *name, int **a, int *rows, int *cols,
                                         ss_error *err);

/* Reads a text vector of integers (labels, maps, landmark indices): one value a line, '#' comments
 * and blank lines skipped.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   out      *out: n malloc'd values (free())
 *   n        their count
 * Errors: SS_ERR_IO (cannot open or read); SS_ERR_PARSE "PATH:LINE: what" (a line with two values, a
 *   non-number, an int out of range); SS_ERR_INVALID on NULL outputs; SS_ERR_NOMEM.
 */
SS_API ss_status ss_read_ints(const char *path, int **out, int *n, ss_error *err);
/* Writes a text vector of integers, one a line.
 *
 * Inputs:
 *   path     the file
 *   v        n values
 *   n        their count (>= 0)
 * Errors: SS_ERR_INVALID on n < 0 or a NULL array; SS_ERR_IO when the file cannot be written.
 */
SS_API ss_status ss_write_ints(const char *path, const int *v, int n, ss_error *err);
/* Reads a text vector of doubles: one value a line ("inf" allowed), '#' comments and blank lines
 * skipped.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   out      *out: n malloc'd values (free())
 *   n        their count
 * Errors: SS_ERR_IO (cannot open or read); SS_ERR_PARSE "PATH:LINE: what" (a line with two values, a
 *   non-number, an int out of range); SS_ERR_INVALID on NULL outputs; SS_ERR_NOMEM.
 */
SS_API ss_status ss_read_doubles(const char *path, double **out, int *n, ss_error *err);
/* Writes a text vector of doubles, one a line, %.17g (write -> read is exact).
 *
 * Inputs:
 *   path     the file
 *   v        n values
 *   n        their count (>= 0)
 * Errors: SS_ERR_INVALID on n < 0 or a NULL array; SS_ERR_IO when the file cannot be written.
 */
SS_API ss_status ss_write_doubles(const char *path, const double *v, int n, ss_error *err);
/* ss_read_ints of len bytes in memory.
 *
 * Inputs:
 *   buf, len the bytes (not kept)
 *   name     stands for PATH in messages (NULL: "<memory>")
 * Outputs:
 *   out, n   as ss_read_ints
 * Errors: as ss_read_ints; SS_ERR_INVALID for a NULL buffer with len > 0.
 */
SS_API ss_status ss_read_ints_memory(const void *buf, size_t len, const char *name, int **out, int *n, ss_error *err);
/* ss_read_doubles of len bytes in memory.
 *
 * Inputs:
 *   buf, len the bytes (not kept)
 *   name     stands for PATH in messages (NULL: "<memory>")
 * Outputs:
 *   out, n   as ss_read_doubles
 * Errors: as ss_read_doubles; SS_ERR_INVALID for a NULL buffer with len > 0.
 */
SS_API ss_status ss_read_doubles_memory(const void *buf, size_t len, const char *name, double **out, int *n,
                                        ss_error *err);
/* ss_read_ints that also returns each value's line number, so that a caller that checks the values
 * (a map against its target mesh) can say "PATH:LINE: ...".
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   out      *out: n malloc'd values (free())
 *   lines    *lines: n malloc'd 1-based line numbers (free())
 *   n        their count
 * Errors: SS_ERR_IO (cannot open or read); SS_ERR_PARSE "PATH:LINE: what" (a line with two values, a
 *   non-number, an int out of range); SS_ERR_INVALID on NULL outputs; SS_ERR_NOMEM.
 */
SS_API ss_status ss_read_ints_lines(const char *path, int **out, int **lines, int *n, ss_error *err);
/* ss_read_ints_lines of len bytes in memory.
 *
 * Inputs:
 *   buf, len the bytes (not kept)
 *   name     stands for PATH in messages (NULL: "<memory>")
 * Outputs:
 *   out, lines, n  as ss_read_ints_lines
 * Errors: as ss_read_ints_lines; SS_ERR_INVALID for a NULL buffer with len > 0.
 */
SS_API ss_status ss_read_ints_lines_memory(const void *buf, size_t len, const char *name, int **out, int **lines, int *n,
                                           ss_error *err);
/* Reads a landmark file: one landmark a line, "i" (the same vertex on both shapes) or "i j" (i on
 * the first shape, j on the second); '#' comments and blank lines skipped.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   lx, ly   *lx, *ly: n malloc'd vertex indices each (free()); ly = lx's values on one-column lines
 *   n        the number of landmarks (>= 1)
 *   columns  (may be NULL) 2 when any line has two indices, else 1
 * Errors: SS_ERR_IO (cannot open or read); SS_ERR_PARSE "PATH:LINE: what" (a negative or non-integer
 *   index, three values on a line, an empty file); SS_ERR_INVALID on NULL outputs; SS_ERR_NOMEM.
 */
SS_API ss_status ss_read_landmarks(const char *path, int **lx, int **ly, int *n, int *columns, ss_error *err);
/* ss_read_landmarks that also returns each landmark's line number, so that a caller that checks
 * them against its meshes can say "PATH:LINE: ...".
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   lx, ly, n, columns  as ss_read_landmarks
 *   lines    (NULL: not wanted) *lines: n malloc'd 1-based line numbers (free())
 * Errors: SS_ERR_IO (cannot open or read); SS_ERR_PARSE "PATH:LINE: what" (a negative or non-integer
 *   index, three values on a line, an empty file); SS_ERR_INVALID on NULL outputs; SS_ERR_NOMEM.
 */
SS_API ss_status ss_read_landmarks_lines(const char *path, int **lx, int **ly, int **lines, int *n, int *columns,
                                         ss_error *err);
/* ss_read_landmarks_lines of len bytes in memory.
 *
 * Inputs:
 *   buf, len the bytes (not kept)
 *   name     stands for PATH in messages (NULL: "<memory>")
 * Outputs:
 *   lx, ly, lines, n, columns  as ss_read_landmarks_lines
 * Errors: as ss_read_landmarks_lines; SS_ERR_INVALID for a NULL buffer with len > 0.
 */
SS_API ss_status ss_read_landmarks_memory(const void *buf, size_t len, const char *name, int **lx, int **ly,
                                          int **lines, int *n, int *columns, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
