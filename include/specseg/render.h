/* specseg — software rendering of meshes to RGB images and PNG files (no GPU, no window). */
#ifndef SPECSEG_RENDER_H
#define SPECSEG_RENDER_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ss_render_options {
  int width, height;           /* output image size in pixels */
  double azimuth, elevation;   /* view direction in degrees; (0,0) looks along -z at the +z side (front, y up) */
  unsigned char background[3];
  int supersample;             /* 1..4: anti-aliasing by rendering s×s samples per pixel */
  double margin;               /* fraction of the image left empty around the shape */
} ss_render_options;

void ss_render_default_options(ss_render_options *o);

/* Rasterise `m` (orthographic, z-buffer, Phong-lit headlight, two-sided) into `rgb` (3*width*height
 * bytes, row-major, top row first). Colours: per-face `face_rgb` (3*nf) wins over per-vertex
 * `vertex_rgb` (3*nv, interpolated); grey when both are NULL. */
ss_status ss_render_mesh(const ss_mesh *m, const unsigned char *vertex_rgb, const unsigned char *face_rgb,
                         const ss_render_options *o, unsigned char *rgb, ss_error *err);

/* 8-bit RGB PNG. */
ss_status ss_write_png(const char *path, const unsigned char *rgb, int width, int height, ss_error *err);

/* Perceptual colormap (viridis-like), t clamped to [0,1]. */
void ss_colormap(double t, unsigned char rgb[3]);
/* Distinct colour for a segment label (well separated hues for the first ~20 labels). */
void ss_label_color(int label, unsigned char rgb[3]);

#ifdef __cplusplus
}
#endif
#endif
