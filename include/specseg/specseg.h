/* specseg — coherent spectral segmentation of 3D shapes and functional-map matching.
 * Umbrella header: one public header per pipeline stage, all with the `ss_` prefix. */
#ifndef SPECSEG_H
#define SPECSEG_H
#include "specseg/core.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/laplacian.h"
#include "specseg/streamline.h"
#include "specseg/spectrum.h"
#include "specseg/geodesic.h"
#include "specseg/fmap.h"
#include "specseg/segment.h"
#include "specseg/eval.h"
#include "specseg/evaluation.h"
#include "specseg/render.h"
#include "specseg/match.h"
#endif
