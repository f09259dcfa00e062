/* specseg — core types: status codes, error messages, the mesh and sparse-matrix structs.
 *
 * Conventions for the whole library:
 *  - plain arrays in and out; the caller owns what it passes in; what a function allocates into an
 *    output struct is released with the matching *_free function;
 *  - every function that can fail returns an ss_status and, when `err` is not NULL, writes a
 *    one-line message into it (files: "PATH:LINE: what"); the library never exits or aborts on input;
 *  - 0-based indices everywhere; vertex arrays are xyz-interleaved (V[3*i+0..2]);
 *  - dense matrices are column-major (Fortran / BLAS order) unless a function says otherwise;
 *  - no hidden state: every function's result depends only on its arguments and the objects passed
 *    in; the library keeps no global mutable data of its own, reads no environment variables and
 *    never prints. Process-wide settings of the libraries it calls are left to the caller (OpenMP's
 *    thread count; OpenBLAS's own threading, which a program that runs specseg calls on several of
 *    its threads should set to 1). One exception is internal and invisible in results: ARPACK
 *    (Fortran, with SAVE variables) is not reentrant, so ss_eigs serialises its ARPACK iterations
 *    across threads with one process-wide lock; concurrent ss_eigs calls are safe, and run their
 *    factorisations and solves in parallel. Likewise imports through assimp (FBX, COLLADA, ...: see io.h)
 *    are serialised by a lock of their own;
 *  - OpenMP is used inside calls only;
 *  - public symbols carry the ss_ prefix (macros SS_ / SPECSEG_); everything else is hidden. */
#ifndef SPECSEG_CORE_H
#define SPECSEG_CORE_H

#include <stddef.h>

#include "specseg/version.h"

/* Marks the functions the shared libraries export (they are built with -fvisibility=hidden). */
#ifndef SS_API
#if defined(__GNUC__) || defined(__clang__)
#define SS_API __attribute__((visibility("default")))
#else
#define SS_API
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ss_status {
  SS_OK = 0,
  SS_ERR_IO = 1,        /* cannot open / read / write a file */
  SS_ERR_PARSE = 2,     /* malformed file content */
  SS_ERR_INVALID = 3,   /* invalid argument or mesh that cannot be processed */
  SS_ERR_NOMEM = 4,     /* allocation failed */
  SS_ERR_NUMERIC = 5,   /* factorisation / eigensolver / solver failure */
  SS_ERR_UNSUPPORTED = 6
} ss_status;

/* A one-line error message, filled by every failing call that is given one. */
typedef struct ss_error {
  char msg[1024];
} ss_error;

/* Writes a printf-style message into e (truncated to 1023 bytes) and returns `code`, so that a
 * function can end with `return ss_fail(err, SS_ERR_INVALID, "...", ...)`.
 *
 * Inputs:
 *   e        the error to fill (NULL: nothing is written)
 *   code     the status to return
 *   fmt, ...  printf format and arguments
 * Returns: code.
 */
SS_API ss_status ss_fail(ss_error *e, ss_status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Short English name of a status ("ok", "invalid input", ...; "unknown status" for a value
 * outside the enum).
 *
 * Inputs:
 *   s        a status
 * Returns: a static string (never NULL; do not free).
 */
SS_API const char *ss_status_name(ss_status s);

/* Triangle mesh: nv vertices (V, 3*nv doubles), nf triangles (F, 3*nf ints, 0-based). */
typedef struct ss_mesh {
  int nv, nf;
  double *V;
  int *F;
} ss_mesh;

/* Allocates a mesh of nv vertices and nf faces; V and F are left uninitialised.
 *
 * Inputs:
 *   nv, nf   vertex and face counts (>= 0)
 * Outputs:
 *   m        zeroed first, then V (3*nv doubles) and F (3*nf ints) malloc'd; free with ss_mesh_free
 * Errors: SS_ERR_INVALID when nv or nf is negative; SS_ERR_NOMEM (m is then zeroed).
 */
SS_API ss_status ss_mesh_alloc(ss_mesh *m, int nv, int nf, ss_error *err); /* V, F uninitialised */
/* Deep copy of a mesh.
 *
 * Inputs:
 *   src      the mesh to copy
 * Outputs:
 *   dst      a new mesh with src's nv, nf, V and F (free with ss_mesh_free)
 * Errors: those of ss_mesh_alloc (SS_ERR_NOMEM).
 */
SS_API ss_status ss_mesh_copy(const ss_mesh *src, ss_mesh *dst, ss_error *err);
/* Frees V and F and zeroes the struct; safe on a zeroed struct and on NULL.
 *
 * Inputs:
 *   m        a mesh from ss_mesh_alloc or any call that fills one
 */
SS_API void ss_mesh_free(ss_mesh *m); /* frees arrays, zeroes the struct; safe on a zeroed struct */
/* Total surface area: the sum of the triangles' areas (indices are not checked).
 *
 * Inputs:
 *   m        the mesh
 * Returns: the area (0 for a mesh without faces).
 */
SS_API double ss_mesh_area(const ss_mesh *m);
/* Length of the diagonal of the axis-aligned bounding box of all nv vertices (referenced or not).
 *
 * Inputs:
 *   m        the mesh
 * Returns: the diagonal (0 for a mesh without vertices).
 */
SS_API double ss_mesh_bbox_diagonal(const ss_mesh *m);

/* Sparse matrix in compressed sparse column form, row indices sorted within each column.
 * Symmetric matrices store both triangles.
 */
typedef struct ss_sparse {
  int nrows, ncols;
  int *colptr;  /* ncols+1 */
  int *rowind;  /* colptr[ncols] */
  double *val;  /* colptr[ncols] */
} ss_sparse;

/* Builds a sparse matrix from (I[k], J[k], X[k]) triplets, summing duplicates.
 *
 * Inputs:
 *   nrows, ncols  the size (>= 0)
 *   nnz      number of triplets
 *   I, J, X  nnz row indices (in [0, nrows)), column indices (in [0, ncols)) and values
 * Outputs:
 *   out      zeroed first, then the CSC matrix (arrays malloc'd; free with ss_sparse_free)
 * Errors: SS_ERR_INVALID on a negative size or an index out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_sparse_from_triplets(int nrows, int ncols, size_t nnz, const int *I, const int *J,
                                         const double *X, ss_sparse *out, ss_error *err);
/* Frees the arrays of A and zeroes it; safe on a zeroed struct and on NULL.
 *
 * Inputs:
 *   A        a matrix from ss_sparse_from_triplets or any call that fills one
 */
SS_API void ss_sparse_free(ss_sparse *A);
/* y = A x.
 *
 * Inputs:
 *   A        nrows x ncols sparse matrix
 *   x        ncols values
 * Outputs:
 *   y        nrows values (overwritten; must not alias x)
 */
SS_API void ss_sparse_matvec(const ss_sparse *A, const double *x, double *y);

/* Wall-clock seconds from a monotonic clock (for differences only).
 *
 * Returns: seconds since an arbitrary fixed point.
 */
SS_API double ss_time(void);

#ifdef __cplusplus
}
#endif
#endif
