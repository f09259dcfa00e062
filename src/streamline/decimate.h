/* Private: quadric-error (Garland & Heckbert 1997) edge-collapse decimation that keeps the topology,
 * used to coarsen very large inputs before the flow (the work mesh is remeshed to ~15k faces anyway).
 * Not public API. */
#ifndef SS_STREAMLINE_DECIMATE_H
#define SS_STREAMLINE_DECIMATE_H

#include "specseg/core.h"

/* Inputs with more vertices than this are coarsened before CMCF by ss_segment (and matched through a
 * coarse proxy by ss_match); at or below it the pipeline is unchanged (FAUST 6,890, TOSCA ≤ 53k). */
#define SSI_COARSEN_ABOVE_NV 100000
/* The coarse mesh's face count before the flow (≈ 50k vertices on a closed surface). */
#define SSI_COARSE_FACES 100000
/* The face count of the proxies ss_match matches very large meshes through (≈ 20k vertices: the
 * segmentation's work mesh has 15k faces, the spectrum k ≤ 120; matching costs grow with it). */
#define SSI_MATCH_PROXY_FACES 40000

/* Decimates `in` (closed, edge- and vertex-manifold, consistently oriented: what ss_remesh takes) to
 * about target_faces faces (never fewer; the count stops above it when no collapse is left that keeps
 * the topology and the orientation of every triangle). The components, their genus and the
 * orientation are kept: every collapse passes the link condition, leaves every vertex of valence
 * ≥ 3 and flips no triangle.
 *
 * out's vertices are input vertices that survived, in input order (moved to the quadric-optimal
 * point); src (may be NULL; out->nv ints, malloc'd) = the input vertex each one was. to_coarse
 * (in->nv ints, caller's) = for every input vertex the nearest coarse vertex found by a greedy walk
 * from the vertex it was merged into (its survivor); -1 for a vertex in no face. */
ss_status ssi_decimate(const ss_mesh *in, int target_faces, ss_mesh *out, int *to_coarse, int **src, ss_error *err);

#endif
