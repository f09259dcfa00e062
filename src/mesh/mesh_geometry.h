/* Internal: triangle measures that neither overflow nor underflow, and the coordinate range the
 * numerical stages accept. Not public API. */
#ifndef SS_MESH_GEOMETRY_H
#define SS_MESH_GEOMETRY_H

#include "specseg/core.h"

/* Area of the triangle (p, q, r). The plain cross-product formula when its squared norm is a normal
 * double (bit for bit what the library always computed); otherwise the same in coordinates scaled
 * by a power of two, so a triangle of size 1e-200 or 1e300 gets its true area (0 when it is really
 * degenerate, +inf when the area itself is beyond the double range). NaN for non-finite input. */
double ssi_triangle_area(const double *p, const double *q, const double *r);

/* |u|² of the longest edge and twice the area, both for the triangle scaled by 2^-e (e returned), with
 * e = 0 whenever the plain values are normal doubles: scale-free ratios (a2 / l2) at any size. */
void ssi_triangle_measures(const double *p, const double *q, const double *r, double *a2, double *l2, int *e);

/* Diagonal of the box [lo, hi] without overflow or underflow (plain formula when it is safe). */
double ssi_box_diagonal(const double *lo, const double *hi);

/* The largest magnitude of a coordinate the numerical stages accept (squared lengths, areas and
 * their products stay finite): 1e70; and the smallest bounding-box diagonal: 1e-70. */
#define SSI_COORD_MAX 1e70
#define SSI_EXTENT_MIN 1e-70

/* Checks the vertices the faces use: finite, |coordinate| <= SSI_COORD_MAX, and a bounding-box
 * diagonal of 0 (left to the callers' zero-area messages) or >= SSI_EXTENT_MIN. SS_ERR_INVALID
 * naming the vertex and what to do, prefixed "what: " (what may be NULL). Unreferenced vertices are not looked at. */
ss_status ssi_mesh_check_coordinates(const ss_mesh *m, const char *what, ss_error *err);

#endif
