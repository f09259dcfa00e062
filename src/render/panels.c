/* Several rendered scenes on one image: a grid of equal panels at one common scale (so sizes compare),
 * a title under each, an optional heading line and an optional colour bar at the right — the layout
 * of `specseg render` with several meshes and of the evaluation's figures. */
#include "specseg/render.h"
#include "util/c_locale.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const unsigned char TEXT_RGB[3] = {30, 30, 30};

void ss_panel_layout_init(ss_panel_layout *l) {
  memset(l, 0, sizeof *l);
  l->titles = 1;
  l->common_scale = 1;
  l->bar_kind = SS_CMAP_VIRIDIS;
  l->bar_lo = 0, l->bar_hi = 1;
  l->bar_row = -1;
}

/* Text scale for a panel height: 1 below 600 px, then one step per 400 px. */
static int text_scale(int height) { return height >= 600 ? 2 + (height - 600) / 400 : 1; }

ss_status ss_render_panels(const ss_panel *panels, int n, const ss_render_options *o, const ss_panel_layout *l,
                           unsigned char **rgb, int *width, int *height, ss_error *err) {
  if (!rgb || !width || !height) return ss_fail(err, SS_ERR_INVALID, "panels: NULL output");
  *rgb = NULL;
  *width = *height = 0;
  if (n < 1 || !panels || !o || !l) return ss_fail(err, SS_ERR_INVALID, "panels: nothing to draw");
  if (o->width < 1 || o->height < 1 || o->width > 16384 || o->height > 16384)
    return ss_fail(err, SS_ERR_INVALID, "panels: bad panel size %dx%d", o->width, o->height);
  ss_render_options po = *o;
  if (l->common_scale && !(po.scale > 0)) {
    double scale = INFINITY;
    for (int k = 0; k < n; k++) {
      if (!panels[k].scene.mesh) continue;
      double s = ss_render_fit_scale(panels[k].scene.mesh, &po);
      if (s > 0 && s < scale) scale = s;
    }
    po.scale = isfinite(scale) ? scale : 0;
  }
  int cols = l->cols <= 0 || l->cols > n ? n : l->cols, rows = (n + cols - 1) / cols;
  int W = po.width, H = po.height, ts = text_scale(H), th = 7 * ts;
  int title_h = l->titles ? th + 6 * ts : 0;
  int head_h = l->heading && *l->heading ? th + 8 * ts : 0;
  /* the bar's column: gap, bar, tick labels (as ss_draw_colorbar prints them) and a margin, and at
   * least the title's width, so nothing is clipped at the image's right edge */
  int bar_w = 0, bar_bw = 6 * ts + 8;
  if (l->colorbar) {
    const double v[3] = {l->bar_hi, 0.5 * (l->bar_lo + l->bar_hi), l->bar_lo};
    int lw = 0, tw = l->bar_title ? ss_text_width(l->bar_title, ts) : 0;
    for (int k = 0; k < 3; k++) {
      char buf[32];
      ssi_snprintf_c(buf, sizeof buf, "%.3g", v[k]);
      if (ss_text_width(buf, ts) > lw) lw = ss_text_width(buf, ts);
    }
    int need = bar_bw + 5 * ts + lw > tw ? bar_bw + 5 * ts + lw : tw; /* labels 5*ts right of the bar */
    bar_w = 4 * ts + need + 6 * ts;
    if (bar_w < W / 4) bar_w = W / 4;
  }
  long cw = (long)cols * W + bar_w, ch = (long)rows * (H + title_h) + head_h;
  if (cw > 32768 || ch > 32768 || cw * ch > 100000000L)
    return ss_fail(err, SS_ERR_INVALID, "panels: image would be %ldx%ld pixels; use smaller panels", cw, ch);
  unsigned char *img = malloc(3 * (size_t)W * H), *canvas = malloc(3 * (size_t)cw * ch);
  if (!img || !canvas) {
    free(img), free(canvas);
    return ss_fail(err, SS_ERR_NOMEM, "panels: out of memory for a %ldx%ld image", cw, ch);
  }
  ss_image_fill(canvas, (int)cw, (int)ch, po.background);
  if (head_h) {
    int tw = ss_text_width(l->heading, ts);
    ss_draw_text(canvas, (int)cw, (int)ch, ((int)cw - tw) / 2 > 0 ? ((int)cw - tw) / 2 : 0, 4 * ts, ts, TEXT_RGB,
                 l->heading);
  }
  for (int k = 0; k < n; k++) {
    int px = (k % cols) * W, py = head_h + (k / cols) * (H + title_h);
    if (panels[k].scene.mesh) {
      ss_status st = ss_render(&panels[k].scene, &po, img, err);
      if (st) {
        free(img), free(canvas);
        return st;
      }
      ss_image_blit(canvas, (int)cw, (int)ch, img, W, H, px, py);
    }
    if (l->titles && panels[k].title && *panels[k].title) {
      int tw = ss_text_width(panels[k].title, ts);
      ss_draw_text(canvas, (int)cw, (int)ch, px + (W - tw) / 2, py + H + 2 * ts, ts, TEXT_RGB, panels[k].title);
    }
  }
  if (l->colorbar) {
    int gh = (int)ch - head_h, bh = (int)(0.6 * rows * H), bx = cols * W + 4 * ts, by = head_h + (gh - bh) / 2;
    if (l->bar_row >= 0 && l->bar_row < rows) /* beside one row: the one the colours belong to */
      bh = (int)(0.6 * H), by = head_h + l->bar_row * (H + title_h) + (H - bh) / 2;
    ss_draw_colorbar(canvas, (int)cw, (int)ch, bx, by, bar_bw, bh, l->bar_kind, l->bar_lo, l->bar_hi,
                     l->bar_title ? l->bar_title : "", ts, TEXT_RGB);
  }
  free(img);
  *rgb = canvas;
  *width = (int)cw, *height = (int)ch;
  return SS_OK;
}
