/* specseg — coherent spectral segmentation of 3D shapes and functional-map matching.
 * Umbrella header of the core library (link with specseg: pkg-config specseg, or the CMake target
 * specseg::specseg). One public header per pipeline stage, all with the `ss_` prefix. The libraries
 * above the core have headers of their own: specseg/synth.h (specseg_synth), specseg/render.h
 * (specseg_render) and specseg/eval.h (specseg_eval). */
#ifndef SPECSEG_H
#define SPECSEG_H
#include "specseg/version.h"
#include "specseg/core.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/laplacian.h"
#include "specseg/streamline.h"
#include "specseg/spectrum.h"
#include "specseg/geodesic.h"
#include "specseg/segment.h"
#include "specseg/fmap.h"
#include "specseg/match.h"
#include "specseg/abi.h"
#endif
