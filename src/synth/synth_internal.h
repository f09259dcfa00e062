/* Private helpers of the synthetic-shape generators (not part of the public API). */
#ifndef SS_SYNTH_INTERNAL_H
#define SS_SYNTH_INTERNAL_H

#include "specseg/core.h"

/* Implicit surface: f < 0 inside, f > 0 outside, |grad f| roughly 1 near the zero set. */
typedef double (*ssi_implicit_fn)(const double p[3], const void *ctx);

/* Marching tetrahedra on a body-centred-cubic lattice of spacing h covering the box [lo, hi] (which
 * must contain the whole surface with a margin). Inside/outside is decided by the strict sign f < 0,
 * so every tetrahedron contributes a consistent piece and the result is always a closed, oriented
 * (outward) 2-manifold, possibly with several components. Triangle quality is poor; see below. */
ss_status ssi_implicit_polygonize_bcc(ssi_implicit_fn f, const void *ctx, const double lo[3],
                                     const double hi[3], double h, ss_mesh *out, ss_error *err);

/* Isotropic remeshing of a closed manifold lying on f = 0, without changing its topology:
 * `iterations` rounds of (short-edge collapses towards edge length L when L > 0, Delaunay edge
 * flips, area-weighted (CVT-like) tangential relaxation with Newton projection back onto f = 0). */
ss_status ssi_implicit_remesh(ssi_implicit_fn f, const void *ctx, ss_mesh *m, double L, int iterations,
                             ss_error *err);

/* Rigid transform x -> R x + t (R row-major). */
typedef struct ssi_rigid {
  double R[9];
  double t[3];
} ssi_rigid;

/* Dual-quaternion skinning: V[i] = blend over bones b of W[i*nb+b] * T[b], applied to V0[i]. */
ss_status ssi_dq_skin(int nv, const double *V0, int nb, const double *W, const ssi_rigid *T, double *V,
                     ss_error *err);

#endif
