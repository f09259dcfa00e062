/* Internal layout of ss_geodesic_mesh. Half-edge h = 3*f + i runs from F[3f+i] to F[3f+(i+1)%3]
 * inside face f. Each half-edge has a local 2D frame: its tail at the origin, its head at (len,0),
 * and the third vertex of its face at (cx, cy) with cy > 0 (faces are counter-clockwise). */
#ifndef SS_GEODESIC_MESH_INTERNAL_H
#define SS_GEODESIC_MESH_INTERNAL_H

#include "specseg/geodesic.h"

#define SS_GV_PSEUDO 1   /* saddle, boundary or cut vertex: emits windows when settled */
#define SS_GV_FULL 2     /* no cyclic corner order (boundary, cut, pinched): emit in every direction */

typedef struct ssi_he_frame {
  double len, cx, cy;
} ssi_he_frame;

struct ss_geodesic_mesh {
  int nv, nf;
  int *F;              /* 3*nf, copy of the faces */
  double *V;           /* 3*nv, copy of the positions (A* bounds of target queries) */
  int *twin;           /* 3*nf, opposite half-edge or -1 (boundary / cut) */
  ssi_he_frame *fr;     /* 3*nf */
  int *vptr, *vcorner; /* CSR vertex -> corners (3*f+i with F[3f+i] == v) */
  unsigned char *vflag;
  double *cang;        /* 3*nf: direction of half-edge h around its tail, cumulative corner angle */
  double *ang;         /* 3*nf: the corner angle at h's tail inside its face (0 for cut-out faces) */
  double *theta;       /* nv: total angle around the vertex */
  double scale;        /* bounding-box diagonal, for tolerances */
};

/* Landmark fields for the lower bounds of target queries: exact distance from nlm landmarks to every
 * vertex of the mesh it was built on (nv vertices), vertex-major lm[v*nlm + k]. */
struct ss_geodesic_landmarks {
  int nv, nlm;
  double *lm;
};


static inline int ssi_he_next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
static inline int ssi_he_prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }

#endif
