/* Line plots (ss_render_plot): curves where their coordinates say, in their colours and width,
 * clipped to the frame; the frame, tick labels, legend and turned y label are drawn; bad input fails. */
#include "specseg/render.h"
#include "testlib.h"

static const unsigned char *px(const unsigned char *img, int w, int x, int y) { return img + 3 * ((size_t)y * w + x); }
static int is(const unsigned char *p, const unsigned char c[3]) { return p[0] == c[0] && p[1] == c[1] && p[2] == c[2]; }

/* the frame's left, right, top and bottom pixel (first black pixels scanned from the middle outwards) */
static void find_frame(const unsigned char *img, int W, int H, int *l, int *r, int *t, int *b) {
  static const unsigned char BLACK[3] = {0, 0, 0};
  int cx = W / 2, cy = H / 2;
  *l = *r = *t = *b = -1;
  for (int x = cx; x >= 0 && *l < 0; x--) if (is(px(img, W, x, cy), BLACK)) *l = x;
  for (int x = cx; x < W && *r < 0; x++) if (is(px(img, W, x, cy), BLACK)) *r = x;
  for (int y = cy; y >= 0 && *t < 0; y--) if (is(px(img, W, cx, y), BLACK)) *t = y;
  for (int y = cy; y < H && *b < 0; y++) if (is(px(img, W, cx, y), BLACK)) *b = y;
}

int main(void) {
  ss_plot p;
  ss_plot_init(&p);
  CHECK(p.width == 1600 && p.height == 1000 && p.legend == 1 && p.xmax == 1 && p.ymax == 1);
  p.width = 800, p.height = 500;
  p.xmin = 0, p.xmax = 0.25, p.ymin = 0, p.ymax = 1, p.yscale = 100;
  p.grid = 0; /* nothing but the curves inside the frame */
  p.title = "CUMULATIVE ERROR", p.xlabel = "GEODESIC ERROR", p.ylabel = "% OF POINTS";
  /* a horizontal line at y = 0.5 (red) and a diagonal (blue) leaving the frame at the top right */
  double hx[2] = {0, 0.25}, hy[2] = {0.5, 0.5}, dx[3] = {0, 0.125, 0.25}, dy[3] = {0, 0.75, 1.5};
  ss_plot_series s[2] = {{2, hx, hy, "RED", {220, 0, 0}}, {3, dx, dy, "BLUE", {0, 0, 220}}};
  p.series = s, p.nseries = 2;
  p.line_width = 4;
  unsigned char *img = NULL;
  CHECK(ss_render_plot(&p, &img, NULL) == SS_OK && img);
  if (!img) return 1;
  const int W = p.width, H = p.height;
  int l, r, top, bot;
  find_frame(img, W, H, &l, &r, &top, &bot);
  CHECK_MSG(l > 0 && r > l + W / 2, "frame columns %d %d", l, r);
  CHECK_MSG(top > 0 && bot > top + H / 2, "frame rows %d %d", top, bot);
  /* the red line sits half-way between the frame's top and bottom, 4 px wide, pure red at its centre */
  const int mid = (top + bot) / 2, xq = l + (r - l) / 4;
  int red_rows = 0, red_c = -1;
  for (int y = top + 2; y < bot - 1; y++) {
    const unsigned char *q = px(img, W, xq, y);
    if (q[0] > 150 && q[1] < 110 && q[2] < 110) red_rows++, red_c = y;
  }
  CHECK_MSG(red_rows >= 3 && red_rows <= 6, "red line %d rows thick", red_rows);
  CHECK_MSG(abs(red_c - mid) <= 4, "red line at row %d, frame middle %d", red_c, mid);
  const unsigned char *q = px(img, W, xq, mid);
  CHECK_MSG(q[0] == 220 && q[1] == 0 && q[2] == 0, "red line centre %d %d %d", q[0], q[1], q[2]);
  /* the blue diagonal passes through (0.125, 0.75): three quarters up, half-way across */
  const int bx = (l + r) / 2, by = bot - (int)lrint(0.75 * (bot - top));
  int blue = 0;
  for (int y = by - 3; y <= by + 3; y++) blue += px(img, W, bx, y)[2] > 150 && px(img, W, bx, y)[0] < 110;
  CHECK_MSG(blue >= 2, "blue line near (%d, %d): %d pixels", bx, by, blue);
  /* it is clipped: nothing blue above the frame (beyond half the line width) */
  int above = 0;
  for (int y = 0; y < top - 3; y++)
    for (int x = l; x <= r; x++) above += px(img, W, x, y)[2] > 150 && px(img, W, x, y)[0] < 60 && px(img, W, x, y)[1] < 60;
  CHECK_MSG(above == 0, "%d blue pixels above the frame", above);
  /* text: the title above the frame, tick labels below it, the y label left of the tick labels */
  int dark_title = 0, dark_below = 0, dark_left = 0;
  for (int y = 0; y < top - 2; y++)
    for (int x = 0; x < W; x++) dark_title += px(img, W, x, y)[0] < 60 && px(img, W, x, y)[2] < 60;
  for (int y = bot + 2; y < H; y++)
    for (int x = 0; x < W; x++) dark_below += px(img, W, x, y)[0] < 60 && px(img, W, x, y)[2] < 60;
  for (int y = top; y < bot; y++)
    for (int x = 0; x < 20; x++) dark_left += px(img, W, x, y)[0] < 60 && px(img, W, x, y)[2] < 60;
  CHECK_MSG(dark_title > 50 && dark_below > 100 && dark_left > 30, "text pixels: title %d, below %d, y label %d", dark_title,
            dark_below, dark_left);
  /* the legend (lower right): a box with a red and a blue line sample */
  int leg_red = 0, leg_blue = 0;
  for (int y = mid + 8; y < bot - 2; y++)
    for (int x = (l + r) / 2 + 20; x < r - 2; x++) {
      const unsigned char *z = px(img, W, x, y);
      leg_red += z[0] == 220 && z[1] == 0 && z[2] == 0;
      leg_blue += z[2] == 220 && z[0] == 0 && z[1] == 0;
    }
  CHECK_MSG(leg_red > 20 && leg_blue > 20, "legend samples: red %d, blue %d", leg_red, leg_blue);
  free(img);
  /* colours of the palette differ */
  unsigned char c0[3], c1[3];
  ss_plot_color(0, c0), ss_plot_color(1, c1);
  CHECK(!is(c0, c1));
  /* errors */
  img = NULL;
  p.xmax = p.xmin;
  CHECK(ss_render_plot(&p, &img, NULL) == SS_ERR_INVALID && !img);
  p.xmax = 0.25, p.width = 10;
  CHECK(ss_render_plot(&p, &img, NULL) == SS_ERR_INVALID);
  p.width = 800, s[0].n = 0;
  CHECK(ss_render_plot(&p, &img, NULL) == SS_ERR_INVALID);
  s[0].n = 2, p.nseries = SS_PLOT_MAX_SERIES + 1;
  CHECK(ss_render_plot(&p, &img, NULL) == SS_ERR_INVALID);
  /* the turned text covers a column band 7 scale wide and its width tall */
  unsigned char canvas[3 * 40 * 100];
  static const unsigned char WHITE[3] = {255, 255, 255}, BLACK[3] = {0, 0, 0};
  ss_image_fill(canvas, 40, 100, WHITE);
  int tw = ss_draw_text_up(canvas, 40, 100, 5, 90, 2, BLACK, "AB1");
  CHECK(tw == ss_text_width("AB1", 2));
  int minx = 99, maxx = -1, miny = 999, maxy = -1;
  for (int y = 0; y < 100; y++)
    for (int x = 0; x < 40; x++)
      if (is(px(canvas, 40, x, y), BLACK)) {
        minx = x < minx ? x : minx, maxx = x > maxx ? x : maxx;
        miny = y < miny ? y : miny, maxy = y > maxy ? y : maxy;
      }
  CHECK_MSG(minx >= 5 && maxx <= 5 + 14 - 1 && maxy <= 89 && miny >= 90 - tw, "turned text box x %d..%d y %d..%d", minx,
            maxx, miny, maxy);
  TEST_MAIN_END();
}
