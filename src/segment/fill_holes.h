/* Internal to the segmentation pipeline: close the boundary loops of a mesh so the remesher (which
 * takes closed surfaces only) can run on shapes with small holes, such as TOSCA's. */
#ifndef SS_SEGMENT_FILL_HOLES_H
#define SS_SEGMENT_FILL_HOLES_H

#include "specseg/core.h"

/* out = in plus, for every boundary loop, one new vertex at the loop's centroid fanned to the loop's
 * edges (orientation consistent with the loop's faces). Vertices 0..in->nv-1 of out are in's, in
 * order. *nholes = number of loops closed (0: out is a plain copy). Fails with SS_ERR_UNSUPPORTED
 * when a vertex has more than one outgoing boundary edge (pinched boundary) or an edge has more than
 * two faces. */
ss_status ssi_fill_holes_fan(const ss_mesh *in, ss_mesh *out, int *nholes, ss_error *err);

#endif
