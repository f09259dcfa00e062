/* Colours: a perceptual sequential colormap and distinct label colours. */
#include "specseg/render.h"

#include <math.h>

/* Anchor colours sampled along the viridis curve (dark blue → green → yellow), interpolated linearly. */
void ss_colormap(double t, unsigned char rgb[3]) {
  static const double A[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},  {44, 113, 142}, {33, 144, 141},
                                 {39, 173, 129}, {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
  if (!(t > 0)) t = 0;
  if (t > 1) t = 1;
  double x = t * 8;
  int i = (int)x;
  if (i > 7) i = 7;
  double f = x - i;
  for (int c = 0; c < 3; c++) rgb[c] = (unsigned char)lround(A[i][c] * (1 - f) + A[i + 1][c] * f);
}

/* White → yellow → orange → red → dark red (ColorBrewer YlOrRd-like anchors), so zero error is white. */
static void heat(double t, unsigned char rgb[3]) {
  static const double A[6][3] = {{255, 255, 255}, {255, 237, 160}, {254, 178, 76},
                                 {240, 59, 32},   {189, 0, 38},    {100, 0, 30}};
  if (!(t > 0)) t = 0;
  if (t > 1) t = 1;
  double x = t * 5;
  int i = (int)x;
  if (i > 4) i = 4;
  double f = x - i;
  for (int c = 0; c < 3; c++) rgb[c] = (unsigned char)lround(A[i][c] * (1 - f) + A[i + 1][c] * f);
}

void ss_colormap_kind_rgb(ss_colormap_kind kind, double t, unsigned char rgb[3]) {
  if (kind == SS_CMAP_HEAT) heat(t, rgb);
  else ss_colormap(t, rgb);
}

void ss_label_color(int label, unsigned char rgb[3]) {
  /* hand-picked, well separated hues first; golden-angle hues afterwards */
  static const unsigned char P[12][3] = {{230, 25, 75},  {60, 180, 75},   {255, 200, 25}, {0, 130, 200},
                                         {245, 130, 48}, {145, 30, 180},  {70, 220, 220}, {240, 50, 230},
                                         {170, 110, 40}, {128, 128, 0},   {0, 128, 128},  {250, 170, 190}};
  if (label < 0) {
    rgb[0] = rgb[1] = rgb[2] = 160;
    return;
  }
  if (label < 12) {
    for (int c = 0; c < 3; c++) rgb[c] = P[label][c];
    return;
  }
  double h = fmod(label * 0.618033988749895, 1.0) * 6, s = 0.65, v = 0.9;
  int i = (int)h;
  double f = h - i, p = v * (1 - s), q = v * (1 - s * f), u = v * (1 - s * (1 - f));
  double r, g, b;
  switch (i % 6) {
    case 0: r = v; g = u; b = p; break;
    case 1: r = q; g = v; b = p; break;
    case 2: r = p; g = v; b = u; break;
    case 3: r = p; g = q; b = v; break;
    case 4: r = u; g = p; b = v; break;
    default: r = v; g = p; b = q; break;
  }
  rgb[0] = (unsigned char)lround(255 * r);
  rgb[1] = (unsigned char)lround(255 * g);
  rgb[2] = (unsigned char)lround(255 * b);
}
