/* Line plots on an RGB image: frame, ticks, grid, anti-aliased curves, legend, title and axis labels
 * in the built-in font (draw.c) — what a cumulative error curve needs, without a plotting library. */
#include "specseg/render.h"
#include "util/c_locale.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ss_plot_init(ss_plot *p) {
  memset(p, 0, sizeof *p);
  p->width = 1600, p->height = 1000;
  p->xmax = p->ymax = 1;
  p->xscale = p->yscale = 1;
  p->legend = 1;
  p->grid = 1;
}

void ss_plot_color(int i, unsigned char rgb[3]) {
  /* ten hues far apart in turn (blue, orange, green, red, purple, brown, pink, grey, olive, cyan) */
  static const unsigned char pal[10][3] = {{31, 99, 180},  {240, 120, 10}, {40, 150, 40},   {210, 35, 40},
                                           {140, 90, 190}, {140, 80, 70},  {220, 100, 180}, {110, 110, 110},
                                           {170, 170, 30}, {20, 180, 200}};
  if (i < 0) i = 0;
  const unsigned char *c = pal[i % 10];
  int dark = i / 10; /* later rounds darker */
  for (int k = 0; k < 3; k++) rgb[k] = (unsigned char)(c[k] * (dark ? 0.6 : 1.0));
}

/* 1, 2 or 5 x 10^k such that range / step lies in [4, 10] (as near as the three mantissas allow) */
static double nice_step(double range) {
  double best = range, bestd = INFINITY;
  double e = floor(log10(range)) - 1;
  for (int k = 0; k < 3; k++, e++)
    for (int m = 0; m < 3; m++) {
      const double mant[3] = {1, 2, 5}, s = mant[m] * pow(10, e), n = range / s;
      double d = n < 4 ? 4 - n : n > 10 ? n - 10 : 0;
      if (d < bestd - 1e-12 || (d <= bestd + 1e-12 && fabs(n - 6) < fabs(range / best - 6))) bestd = d, best = s;
    }
  return best;
}

/* the decimals a tick label needs: step x scale printed exactly (at most 6) */
static int tick_decimals(double step) {
  int d = 0;
  double v = fabs(step);
  while (d < 6 && fabs(v * pow(10, d) - round(v * pow(10, d))) > 1e-6 * fmax(1, v * pow(10, d))) d++;
  return d;
}

static void tick_label(char *buf, size_t n, double v, int dec) {
  if (fabs(v) < 0.5 * pow(10, -dec)) v = 0; /* no "-0.00" */
  ssi_snprintf_c(buf, n, "%.*f", dec, v);
}

/* distance from (px, py) to the segment a-b */
static double seg_dist(double px, double py, double ax, double ay, double bx, double by) {
  double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy, t = 0;
  if (l2 > 0) t = ((px - ax) * dx + (py - ay) * dy) / l2;
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  double ex = ax + t * dx - px, ey = ay + t * dy - py;
  return sqrt(ex * ex + ey * ey);
}

/* coverage of a polyline of constant half width hw in cov (w x h, clip rectangle cx0..cx1, cy0..cy1):
 * the largest coverage over its segments, so joints are not drawn twice */
static void polyline_coverage(float *cov, int w, int h, const double *X, const double *Y, int n, double hw, int cx0,
                              int cy0, int cx1, int cy1) {
  for (int i = 0; i + 1 < n || (n == 1 && i == 0); i++) {
    double ax = X[i], ay = Y[i], bx = n == 1 ? ax : X[i + 1], by = n == 1 ? ay : Y[i + 1];
    if (!isfinite(ax) || !isfinite(ay) || !isfinite(bx) || !isfinite(by)) continue;
    int x0 = (int)floor(fmin(ax, bx) - hw - 1), x1 = (int)ceil(fmax(ax, bx) + hw + 1);
    int y0 = (int)floor(fmin(ay, by) - hw - 1), y1 = (int)ceil(fmax(ay, by) + hw + 1);
    if (x0 < cx0) x0 = cx0;
    if (y0 < cy0) y0 = cy0;
    if (x1 > cx1) x1 = cx1;
    if (y1 > cy1) y1 = cy1;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > w) x1 = w;
    if (y1 > h) y1 = h;
    for (int yy = y0; yy < y1; yy++)
      for (int xx = x0; xx < x1; xx++) {
        double d = seg_dist(xx + 0.5, yy + 0.5, ax, ay, bx, by), c = hw + 0.5 - d;
        if (c <= 0) continue;
        if (c > 1) c = 1;
        float *p = cov + (size_t)yy * w + xx;
        if (c > *p) *p = (float)c;
      }
  }
}

static void composite(unsigned char *rgb, const float *cov, int w, int h, const unsigned char c[3]) {
  for (size_t i = 0; i < (size_t)w * h; i++) {
    float a = cov[i];
    if (a <= 0) continue;
    for (int k = 0; k < 3; k++) rgb[3 * i + k] = (unsigned char)lrint(rgb[3 * i + k] * (1 - a) + c[k] * a);
  }
}

ss_status ss_render_plot(const ss_plot *p, unsigned char **out, ss_error *err) {
  if (!p || !out) return ss_fail(err, SS_ERR_INVALID, "plot: no plot or output");
  *out = NULL;
  const int W = p->width, H = p->height;
  if (W < 64 || H < 64 || W > 16384 || H > 16384)
    return ss_fail(err, SS_ERR_INVALID, "plot: size %d x %d outside 64..16384", W, H);
  if (!(p->xmax > p->xmin) || !(p->ymax > p->ymin) || !isfinite(p->xmax - p->xmin) || !isfinite(p->ymax - p->ymin))
    return ss_fail(err, SS_ERR_INVALID, "plot: empty range x [%g, %g], y [%g, %g]", p->xmin, p->xmax, p->ymin, p->ymax);
  if (p->nseries < 0 || p->nseries > SS_PLOT_MAX_SERIES || (p->nseries > 0 && !p->series))
    return ss_fail(err, SS_ERR_INVALID, "plot: %d series (at most %d)", p->nseries, SS_PLOT_MAX_SERIES);
  for (int s = 0; s < p->nseries; s++)
    if (p->series[s].n < 1 || !p->series[s].x || !p->series[s].y)
      return ss_fail(err, SS_ERR_INVALID, "plot: series %d has no points", s);
  unsigned char *rgb = malloc((size_t)3 * W * H);
  float *cov = malloc(sizeof(float) * (size_t)W * H);
  double *PX = NULL, *PY = NULL;
  int nmax = 2;
  for (int s = 0; s < p->nseries; s++) nmax = p->series[s].n > nmax ? p->series[s].n : nmax;
  PX = malloc(sizeof(double) * (size_t)nmax), PY = malloc(sizeof(double) * (size_t)nmax);
  if (!rgb || !cov || !PX || !PY) {
    free(rgb), free(cov), free(PX), free(PY);
    return ss_fail(err, SS_ERR_NOMEM, "plot: out of memory");
  }
  static const unsigned char WHITE[3] = {255, 255, 255}, BLACK[3] = {0, 0, 0}, GRID[3] = {222, 222, 222},
                             GREY[3] = {150, 150, 150};
  ss_image_fill(rgb, W, H, WHITE);
  const int ts = p->text_scale > 0 ? p->text_scale : (H / 300 > 1 ? H / 300 : 1), th = 7 * ts;
  const double lw = p->line_width > 0 ? p->line_width : fmax(2.0, H / 260.0);
  const int fw = ts > 1 ? ts / 2 + 1 : 1; /* frame and tick line width */
  const double xmul = p->xscale != 0 ? p->xscale : 1, ymul = p->yscale != 0 ? p->yscale : 1;
  const double xs = p->xtick > 0 ? p->xtick : nice_step(p->xmax - p->xmin);
  const double ys = p->ytick > 0 ? p->ytick : nice_step(p->ymax - p->ymin);
  const int xdec = tick_decimals(xs * xmul), ydec = tick_decimals(ys * ymul);
  /* the widest y tick label sets the left margin */
  char buf[64];
  int ylw = 0;
  for (double v = ceil(p->ymin / ys - 1e-9) * ys; v <= p->ymax + 1e-9 * ys; v += ys) {
    tick_label(buf, sizeof buf, v * ymul, ydec);
    int tw = ss_text_width(buf, ts);
    ylw = tw > ylw ? tw : ylw;
  }
  const int left = (p->ylabel && *p->ylabel ? 2 * th : 0) + ylw + 2 * th, right = 3 * th;
  const int top = p->title && *p->title ? 3 * th : 2 * th, bottom = th + 2 * th + (p->xlabel && *p->xlabel ? 2 * th : 0) + th;
  const int x0 = left, x1 = W - right, y0 = top, y1 = H - bottom;
  if (x1 - x0 < 16 || y1 - y0 < 16) {
    free(rgb), free(cov), free(PX), free(PY);
    return ss_fail(err, SS_ERR_INVALID, "plot: %d x %d leaves no room for the axes at text scale %d", W, H, ts);
  }
  const double sx = (x1 - x0) / (p->xmax - p->xmin), sy = (y1 - y0) / (p->ymax - p->ymin);
#define PXX(v) (x0 + ((v) - p->xmin) * sx)
#define PYY(v) (y1 - ((v) - p->ymin) * sy)
  /* grid and ticks */
  for (double v = ceil(p->xmin / xs - 1e-9) * xs; v <= p->xmax + 1e-9 * xs; v += xs) {
    int px = (int)lrint(PXX(v));
    if (p->grid) ss_image_rect(rgb, W, H, px, y0, fw, y1 - y0, GRID);
    ss_image_rect(rgb, W, H, px - fw / 2, y1, fw, th / 2, BLACK);
    tick_label(buf, sizeof buf, v * xmul, xdec);
    ss_draw_text(rgb, W, H, px - ss_text_width(buf, ts) / 2, y1 + th, ts, BLACK, buf);
  }
  for (double v = ceil(p->ymin / ys - 1e-9) * ys; v <= p->ymax + 1e-9 * ys; v += ys) {
    int py = (int)lrint(PYY(v));
    if (p->grid) ss_image_rect(rgb, W, H, x0, py, x1 - x0, fw, GRID);
    ss_image_rect(rgb, W, H, x0 - th / 2, py - fw / 2, th / 2, fw, BLACK);
    tick_label(buf, sizeof buf, v * ymul, ydec);
    ss_draw_text(rgb, W, H, x0 - th - ss_text_width(buf, ts), py - th / 2, ts, BLACK, buf);
  }
  /* curves, each clipped to the frame widened by half the line (a curve along the frame stays whole) */
  const int pad = (int)ceil(lw / 2);
  for (int s = 0; s < p->nseries; s++) {
    const ss_plot_series *q = &p->series[s];
    for (int i = 0; i < q->n; i++) PX[i] = PXX(q->x[i]), PY[i] = PYY(q->y[i]);
    memset(cov, 0, sizeof(float) * (size_t)W * H);
    polyline_coverage(cov, W, H, PX, PY, q->n, lw / 2, x0 - pad, y0 - pad, x1 + pad, y1 + pad);
    composite(rgb, cov, W, H, q->rgb);
  }
  /* frame on top */
  ss_image_rect(rgb, W, H, x0 - fw / 2, y0 - fw / 2, x1 - x0 + fw, fw, BLACK);
  ss_image_rect(rgb, W, H, x0 - fw / 2, y1 - fw / 2, x1 - x0 + fw, fw, BLACK);
  ss_image_rect(rgb, W, H, x0 - fw / 2, y0 - fw / 2, fw, y1 - y0 + fw, BLACK);
  ss_image_rect(rgb, W, H, x1 - fw / 2, y0 - fw / 2, fw, y1 - y0 + fw, BLACK);
  /* legend */
  int nleg = 0, legw = 0;
  for (int s = 0; s < p->nseries; s++)
    if (p->series[s].label && *p->series[s].label) {
      nleg++;
      int tw = ss_text_width(p->series[s].label, ts);
      legw = tw > legw ? tw : legw;
    }
  if (p->legend > 0 && nleg > 0) {
    const int row = 2 * th, sample = 4 * th, bw = th + sample + th + legw + th, bh = nleg * row + th;
    int bx = p->legend == 2 || p->legend == 4 ? x0 + th : x1 - th - bw;
    int by = p->legend == 2 || p->legend == 3 ? y0 + th : y1 - th - bh;
    ss_image_rect(rgb, W, H, bx, by, bw, bh, WHITE);
    ss_image_rect(rgb, W, H, bx, by, bw, fw, GREY);
    ss_image_rect(rgb, W, H, bx, by + bh - fw, bw, fw, GREY);
    ss_image_rect(rgb, W, H, bx, by, fw, bh, GREY);
    ss_image_rect(rgb, W, H, bx + bw - fw, by, fw, bh, GREY);
    int k = 0;
    for (int s = 0; s < p->nseries; s++) {
      const ss_plot_series *q = &p->series[s];
      if (!q->label || !*q->label) continue;
      double cy = by + th + k * row + th / 2.0, lx[2] = {bx + th, bx + th + sample}, ly[2] = {cy, cy};
      memset(cov, 0, sizeof(float) * (size_t)W * H);
      polyline_coverage(cov, W, H, lx, ly, 2, lw / 2, 0, 0, W, H);
      composite(rgb, cov, W, H, q->rgb);
      ss_draw_text(rgb, W, H, bx + 2 * th + sample, (int)lrint(cy) - th / 2, ts, BLACK, q->label);
      k++;
    }
  }
  /* texts */
  if (p->title && *p->title) {
    int tw = ss_text_width(p->title, ts);
    ss_draw_text(rgb, W, H, (x0 + x1) / 2 - tw / 2, th, ts, BLACK, p->title);
  }
  if (p->xlabel && *p->xlabel) {
    int tw = ss_text_width(p->xlabel, ts);
    ss_draw_text(rgb, W, H, (x0 + x1) / 2 - tw / 2, y1 + 3 * th, ts, BLACK, p->xlabel);
  }
  if (p->ylabel && *p->ylabel) {
    int tw = ss_text_width(p->ylabel, ts);
    ss_draw_text_up(rgb, W, H, th / 2 + ts, (y0 + y1) / 2 + tw / 2, ts, BLACK, p->ylabel);
  }
#undef PXX
#undef PYY
  free(cov), free(PX), free(PY);
  *out = rgb;
  return SS_OK;
}
