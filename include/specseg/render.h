/* specseg — software rendering of meshes to RGB images and PNG files (no GPU, no window).
 *
 * Images are 8-bit RGB, 3*width*height bytes, row-major, top row first. The rasteriser is
 * orthographic with a z-buffer and deferred per-sample Blinn-Phong shading under a headlight;
 * anti-aliasing by supersampling. Extras: isolines of a scalar field (screen-space, constant width),
 * marker spheres (ray-cast impostors, z-tested against the mesh), and 2-D drawing helpers for
 * panels, text and colour bars. */
#ifndef SPECSEG_RENDER_H
#define SPECSEG_RENDER_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ss_render_options {
  int width, height;           /* output image size in pixels */
  double azimuth, elevation;   /* view direction in degrees; (0,0) looks along -z at the +z side (front, y up);
                                  azimuth turns the camera about +y, elevation raises it towards +y */
  unsigned char background[3];
  int supersample;             /* 1..4: anti-aliasing by rendering s×s samples per pixel (default 2) */
  double margin;               /* fraction of the image left empty around the shape (default 0.05) */
  double scale;                /* output pixels per world unit; 0 (default) = fit the mesh into the image.
                                  Give several panels the same scale (ss_render_fit_scale) to compare sizes. */
  int up;                      /* the world axis drawn upwards (ss_up_axis): 0 (default) or SS_UP_Y = +y;
                                  the view (azimuth, elevation) is then taken about that axis */
} ss_render_options;

/* World axes for ss_render_options.up. The mesh is first turned so that this axis points up (+y of the
 * view): +z up (TOSCA, most CAD / 3-D printing files) turns (x, y, z) into (x, z, -y), so the front view
 * looks along +y; +x turns it into (-y, x, z); -y into (-x, -y, z); -z into (x, -z, y); -x into (y, -x, z). */
typedef enum ss_up_axis {
  SS_UP_NEG_Z = -3, SS_UP_NEG_Y = -2, SS_UP_NEG_X = -1, SS_UP_DEFAULT = 0, SS_UP_X = 1, SS_UP_Y = 2, SS_UP_Z = 3
} ss_up_axis;

/* The up axis of n meshes drawn together (NULL entries skipped), by a fixed rule on their vertices:
 * along each axis the "base" is the set of vertices within 1% of the axis's extent from its minimum,
 * and its spread is the area of the base's bounding rectangle in the other two axes divided by the
 * mesh's bounding rectangle there (feet or paws on a floor spread wide; a nose, a hand or a flank do
 * not). The axis with the largest spread, averaged over the meshes, is up (always the positive
 * direction: files store shapes standing, not upside down) when that spread is at least 0.05;
 * otherwise (no clear base) +z, unless z is the shortest side of the first mesh's bounding box, then +y.
 * Gives +y on all 100 FAUST shapes but 3 and +z on all 76 TOSCA shapes but 4 (strongly posed ones).
 * SS_UP_Y when there is no vertex. */
SS_API ss_up_axis ss_render_guess_up(const ss_mesh *const *meshes, int n);

/* sizeof the render library's public struct named "ss_render_options" or "ss_render_scene" (for
 * bindings that mirror them, as ss_struct_size in abi.h); 0 for an unknown name. */
SS_API size_t ss_render_struct_size(const char *name);
SS_API void ss_render_default_options(ss_render_options *o);

/* What to draw. Start from ss_render_scene_init (mesh set, everything else off). */
typedef struct ss_render_scene {
  const ss_mesh *mesh;
  const unsigned char *vertex_rgb; /* 3*nv, interpolated; NULL: grey */
  const unsigned char *face_rgb;   /* 3*nf, flat; wins over vertex_rgb */
  const double *scalar;            /* nv values whose isolines are drawn (NULL: none) */
  int isolines;                    /* number of levels, evenly spaced strictly inside [smin, smax] */
  double scalar_min, scalar_max;   /* level range; scalar_min >= scalar_max: the field's finite range */
  unsigned char isoline_rgb[3];    /* default dark grey */
  int nmarkers;                    /* small spheres, e.g. segment centres and landmarks */
  const double *markers;           /* 3*nmarkers centres in world coordinates */
  const unsigned char *marker_rgb; /* 3*nmarkers, NULL: black */
  double marker_radius;            /* world units; <= 0: 1.2% of the mesh's bounding-box diagonal */
} ss_render_scene;

SS_API void ss_render_scene_init(ss_render_scene *s, const ss_mesh *m);

/* Render the scene into `rgb`. Fails (SS_ERR_INVALID) on bad sizes, face indices out of range, a NULL
 * marker array with nmarkers > 0; SS_ERR_NOMEM when the buffers cannot be allocated. */
SS_API ss_status ss_render(const ss_render_scene *s, const ss_render_options *o, unsigned char *rgb, ss_error *err);

/* Shorthand: the mesh with per-face colours `face_rgb` (wins) or per-vertex `vertex_rgb`, grey when both
 * are NULL. */
SS_API ss_status ss_render_mesh(const ss_mesh *m, const unsigned char *vertex_rgb, const unsigned char *face_rgb,
                                const ss_render_options *o, unsigned char *rgb, ss_error *err);

/* The scale (pixels per world unit) at which `m`, seen from o's view, fills o's image minus margins.
 * The smallest over several meshes shows them all at one common scale. 0 for an empty mesh. */
SS_API double ss_render_fit_scale(const ss_mesh *m, const ss_render_options *o);

/* 8-bit RGB PNG. */
SS_API ss_status ss_write_png(const char *path, const unsigned char *rgb, int width, int height, ss_error *err);

/* ---- colours ---------------------------------------------------------------------------------- */

typedef enum ss_colormap_kind {
  SS_CMAP_VIRIDIS = 0, /* perceptual sequential, dark blue → green → yellow (scalar fields) */
  SS_CMAP_HEAT = 1     /* white → yellow → red → dark red (errors: 0 is white) */
} ss_colormap_kind;

/* Perceptual colormap (viridis-like), t clamped to [0,1]; NaN maps to 0. */
SS_API void ss_colormap(double t, unsigned char rgb[3]);
SS_API void ss_colormap_kind_rgb(ss_colormap_kind kind, double t, unsigned char rgb[3]);
/* Distinct colour for a segment label (well separated hues for the first ~20 labels); < 0: grey. */
SS_API void ss_label_color(int label, unsigned char rgb[3]);

/* Per-face colours of a segmentation (labels: one per vertex, -1 = none): a face whose three corners
 * share label l gets ss_label_color(l), faces across segments get `neutral` (NULL: light grey
 * 225,225,220) — the paper's convention for boundary triangles. face_rgb: 3*nf bytes. */
SS_API ss_status ss_segmentation_face_colors(const ss_mesh *m, const int *labels, const unsigned char *neutral,
                                             unsigned char *face_rgb, ss_error *err);
/* Renumber `labels` (n vertices, ids >= -1) in place so that its segment ids agree with `ref` on the same
 * vertices where they overlap most (greedy on the overlap counts, each reference id used once); segments
 * left without a partner get ids after the reference's largest. Gives corresponding segments of shapes
 * in correspondence (e.g. FAUST poses, identity ground truth) the same colour. */
SS_API ss_status ss_labels_align(int *labels, const int *ref, int n, ss_error *err);

/* ---- 2-D drawing on an RGB image (everything clipped to the image) ------------------------------ */

SS_API void ss_image_fill(unsigned char *rgb, int w, int h, const unsigned char c[3]);
/* Copy a sw x sh image into dst at (x, y). */
SS_API void ss_image_blit(unsigned char *dst, int dw, int dh, const unsigned char *src, int sw, int sh, int x, int y);
SS_API void ss_image_rect(unsigned char *rgb, int w, int h, int x, int y, int rw, int rh, const unsigned char c[3]);
/* Text in a built-in 5x7 pixel font, each font pixel drawn as a scale x scale block; (x, y) is the
 * top-left corner. Covers digits, letters (lower case drawn as upper case), space and
 * . , - + : / % ( ) = _ # < > * [ ] '; other characters are drawn as a box. Returns the width drawn
 * in pixels. */
SS_API int ss_draw_text(unsigned char *rgb, int w, int h, int x, int y, int scale, const unsigned char c[3],
                        const char *text);
/* The same text turned a quarter counter-clockwise (reading upwards, as a y-axis label): (x, y) is
 * the bottom-left corner of the turned text, which covers columns x .. x + 7 scale - 1 and rows
 * y - width .. y - 1 (width = ss_text_width). Returns the width (its height on the image). */
SS_API int ss_draw_text_up(unsigned char *rgb, int w, int h, int x, int y, int scale, const unsigned char c[3],
                           const char *text);
SS_API int ss_text_width(const char *text, int scale);
/* A vertical colour bar with its range written beside it: the box (x, y, bw, bh), hi at the top,
 * tick labels lo, mid and hi (printf %.3g) in `text_rgb` to its right, and an optional title above. */
SS_API void ss_draw_colorbar(unsigned char *rgb, int w, int h, int x, int y, int bw, int bh, ss_colormap_kind kind,
                             double lo, double hi, const char *title, int text_scale, const unsigned char text_rgb[3]);

/* ---- colours of maps and fields (map_colors.c, scalar_colors.c) -------------------------------- */

/* Smooth per-vertex colours from the positions normalised to the bounding box (x → red, y → green,
 * z → blue, each in [0.12, 0.97] of full scale): the "texture" a map transfers. rgb: 3*nv bytes. */
SS_API void ss_coordinate_colors(const ss_mesh *m, unsigned char *rgb);
/* The same with a smooth 3-D checker pattern darkening half of its cells (cell size period/2 times
 * the bounding-box diagonal): shows where a map shifts or turns a part (e.g. the head) by less than
 * the colour ramps can reveal. period <= 0: plain ss_coordinate_colors. */
SS_API void ss_coordinate_pattern_colors(const ss_mesh *m, double period, unsigned char *rgb);
/* Colour transfer through a point map (pull-back): out[i] = target_rgb[map[i]] for the nx source
 * vertices. SS_ERR_INVALID on a map entry outside [0, ny). */
SS_API ss_status ss_map_transfer_colors(int nx, const int *map, int ny, const unsigned char *target_rgb, unsigned char *out,
                                        ss_error *err);
/* Per-vertex colours of a field: colormap `kind` over [lo, hi] (clamped); non-finite values grey. */
SS_API void ss_scalar_colors(const double *v, int n, ss_colormap_kind kind, double lo, double hi, unsigned char *rgb);

/* ---- panels: several scenes on one image (panels.c) ------------------------------------------- */

typedef struct ss_panel {
  ss_render_scene scene; /* scene.mesh NULL: an empty cell */
  const char *title;     /* written under the panel; NULL or "": none */
} ss_panel;

typedef struct ss_panel_layout {
  int cols;                  /* panels per row; <= 0 (default) or > n: all in one row */
  int titles;                /* 1 (default): a line of text under each panel */
  int common_scale;          /* 1 (default): all panels at the smallest fit scale (unless o->scale > 0) */
  int colorbar;              /* 1: a colour bar right of the grid for bar_kind over [bar_lo, bar_hi] */
  ss_colormap_kind bar_kind;
  double bar_lo, bar_hi;
  const char *bar_title;
  int bar_row;               /* -1 (default): the bar centred on the grid; r >= 0: beside row r only */
  const char *heading;       /* NULL (default): none; else a line of text above the grid */
} ss_panel_layout;

SS_API void ss_panel_layout_init(ss_panel_layout *l);

/* Renders the n panels, o->width x o->height pixels each, row by row into a grid (text scale grows
 * with the panel height) and returns the malloc'd image in *rgb (*width x *height). SS_ERR_INVALID on
 * bad sizes or an image beyond 32768 pixels a side or 10^8 pixels; ss_render's errors for the
 * scenes. */
SS_API ss_status ss_render_panels(const ss_panel *panels, int n, const ss_render_options *o, const ss_panel_layout *l,
                                  unsigned char **rgb, int *width, int *height, ss_error *err);

/* ---- a comparison of point maps X -> Y, as the paper's Figures 9–11 (map_comparison.c) ---------- */

#define SS_MAP_COMPARISON_MAX 4

/* What the figure shows. Start from ss_map_comparison_init; maps, errors and means are required,
 * everything else optional (NULL / 0: not drawn). */
typedef struct ss_map_comparison {
  const ss_mesh *x, *y;                        /* the maps go from X's vertices to Y's */
  const char *x_name, *y_name;                 /* in the titles "Y NAME" and "X NAME via GT" */
  int nmaps;                                   /* 1..SS_MAP_COMPARISON_MAX */
  const int *map[SS_MAP_COMPARISON_MAX];       /* x->nv entries: line i = vertex of Y for vertex i of X */
  const double *error[SS_MAP_COMPARISON_MAX];  /* x->nv per-vertex errors (e.g. ss_map_geodesic_error's) */
  double mean_error[SS_MAP_COMPARISON_MAX];    /* written under each heat map */
  const char *method[SS_MAP_COMPARISON_MAX];   /* e.g. "STD": titles "STD" and "STD mean 0.0312" */
  const int *gt;                 /* ground truth X -> Y (x->nv): X pulled back through it, bottom left */
  double error_max;              /* top of the shared heat scale; <= 0 (default): the pooled 95th
                                    percentile of all errors rounded up to 1, 2, 2.5 or 5 x 10^k */
  double checker_period;         /* Y's colours: ss_coordinate_pattern_colors(period); default 0.06 */
  int nlandmarks;                /* white spheres on Y and on X's colour transfers */
  const int *landmarks_x, *landmarks_y;
  /* segments (labels_x NULL: no segment column): labels 0..segments-1 per vertex (-1: none), centres
   * drawn black (NULL: none); paired segments (pair_x[p] on X with pair_y[p] on Y) share a colour,
   * unpaired ones and boundary triangles are grey */
  int segments_x, segments_y;
  const int *labels_x, *labels_y, *centers_x, *centers_y;
  int npairs;
  const int *pair_x, *pair_y;
  const char *heading;           /* a line above the panels; NULL: none */
} ss_map_comparison;

SS_API void ss_map_comparison_init(ss_map_comparison *c, const ss_mesh *x, const ss_mesh *y);

/* Two rows of o->width x o->height panels at one scale (ss_render_panels): top, Y coloured by its
 * coordinates, then X pulled back through each map (colour transfer), then X's segments; bottom, X
 * pulled back through the ground truth (what a perfect map shows above; an empty cell without gt),
 * each map's error as a heat map on the shared scale with its colour bar beside the row, then Y's
 * segments. Returns the malloc'd image in *rgb (*width x *height) and the scale's top in *error_max
 * (may be NULL). SS_ERR_INVALID on a missing map, a map, gt, landmark, label, centre or pair out of
 * range; ss_render_panels' errors. */
SS_API ss_status ss_render_map_comparison(const ss_map_comparison *c, const ss_render_options *o, unsigned char **rgb,
                                          int *width, int *height, double *error_max, ss_error *err);

/* ---- line plots (plot.c) ------------------------------------------------------------------------ */

#define SS_PLOT_MAX_SERIES 16

/* One curve: n points (x[i], y[i]) joined by straight segments, in colour rgb, named in the legend. */
typedef struct ss_plot_series {
  int n;
  const double *x, *y;
  const char *label; /* NULL or "": not in the legend */
  unsigned char rgb[3];
} ss_plot_series;

/* A line plot. Start from ss_plot_init (1600 x 1000 pixels, white, no series), then set the ranges,
 * texts and series. */
typedef struct ss_plot {
  int width, height;              /* image size in pixels (default 1600 x 1000) */
  double xmin, xmax, ymin, ymax;  /* the axes' ranges (default [0, 1] each); points outside are clipped */
  double xtick, ytick;            /* tick spacing; <= 0 (default): 1, 2 or 5 x 10^k giving 4..10 ticks */
  double xscale, yscale;          /* tick labels show value x scale (default 1; e.g. 100 for percent) */
  const char *title, *xlabel, *ylabel; /* NULL: none; the y label reads upwards */
  int nseries;                    /* 0 .. SS_PLOT_MAX_SERIES */
  const ss_plot_series *series;
  double line_width;              /* curve width in pixels; <= 0 (default): height / 260, at least 2 */
  int text_scale;                 /* font pixel size; <= 0 (default): height / 300, at least 1 */
  int legend;                     /* where the legend goes: 0 none, 1 lower right (default), 2 upper left,
                                     3 upper right, 4 lower left */
  int grid;                       /* 1 (default): light grid lines at the ticks */
} ss_plot;

SS_API void ss_plot_init(ss_plot *p);
/* A colour for series i that stays distinct from its neighbours for the first ~10 (then repeats
 * darker). */
SS_API void ss_plot_color(int i, unsigned char rgb[3]);
/* Draws the plot: frame, ticks with labels, grid, anti-aliased curves (each of constant width, its
 * joints without overlaps) clipped to the frame, the legend (a line sample beside each label), title
 * and axis labels, into a malloc'd 3 x width x height RGB image *rgb. SS_ERR_INVALID on sizes outside
 * 64..16384, an empty range, more than SS_PLOT_MAX_SERIES series or a series without points;
 * SS_ERR_NOMEM. */
SS_API ss_status ss_render_plot(const ss_plot *p, unsigned char **rgb, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
