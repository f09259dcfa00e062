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

/* How to render: image size, view, background, anti-aliasing, framing (start from
 * ss_render_default_options).
 */
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

/* The up axis of n meshes drawn together, by a fixed rule on their vertices: along each axis the
 * "base" is the set of vertices within 1% of the axis's extent from its minimum, and its spread is the
 * area of the base's bounding rectangle in the other two axes divided by the mesh's bounding rectangle
 * there (feet or paws on a floor spread wide; a nose, a hand or a flank do not). The axis with the
 * largest spread, averaged over the meshes, is up (always the positive direction: files store shapes
 * standing, not upside down) when that spread is at least 0.05; otherwise (no clear base) +z, unless z
 * is the shortest side of the first mesh's bounding box, then +y. Gives +y on all 100 FAUST shapes but
 * 3 and +z on all 76 TOSCA shapes but 4 (strongly posed ones).
 *
 * Inputs:
 *   meshes   n meshes (NULL entries skipped)
 * Returns: SS_UP_X, SS_UP_Y or SS_UP_Z; SS_UP_Y when there is no vertex.
 */
SS_API ss_up_axis ss_render_guess_up(const ss_mesh *const *meshes, int n);

/* sizeof of the render library's public structs, by name, for bindings that mirror them (as
 * ss_struct_size in abi.h).
 *
 * Inputs:
 *   name     "ss_render_options" or "ss_render_scene"
 * Returns: the size in bytes; 0 for an unknown name.
 */
SS_API size_t ss_render_struct_size(const char *name);
/* Fills o with the defaults: 800 x 800 pixels, front view (azimuth and elevation 0), white
 * background, supersample 2, margin 0.05, scale 0 (fit), up 0 (+y).
 *
 * Outputs:
 *   o        every field written
 */
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

/* Starts a scene: the mesh set, everything else off (no colours: grey; no isolines, no markers),
 * isoline colour dark grey.
 *
 * Inputs:
 *   m        the mesh to draw (borrowed)
 * Outputs:
 *   s        every field written
 */
SS_API void ss_render_scene_init(ss_render_scene *s, const ss_mesh *m);

/* Renders a scene into an RGB image (orthographic, z-buffered, Blinn-Phong under a headlight,
 * supersampled; isolines and marker spheres as the scene asks).
 *
 * Inputs:
 *   s        the scene
 *   o        options (not NULL; start from ss_render_default_options)
 * Outputs:
 *   rgb      3·width·height bytes, row-major, top row first (caller-allocated)
 * Errors: SS_ERR_INVALID on a NULL argument, bad sizes, face indices out of range, a NULL marker
 *   array with nmarkers > 0; SS_ERR_NOMEM when the buffers cannot be allocated.
 */
SS_API ss_status ss_render(const ss_render_scene *s, const ss_render_options *o, unsigned char *rgb, ss_error *err);

/* Shorthand for ss_render of a mesh with per-face colours face_rgb (wins) or per-vertex vertex_rgb,
 * grey when both are NULL.
 *
 * Inputs:
 *   m        the mesh
 *   vertex_rgb  NULL or 3*nv bytes
 *   face_rgb NULL or 3*nf bytes
 *   o        options (not NULL; start from ss_render_default_options)
 * Outputs:
 *   rgb      3·width·height bytes (caller-allocated)
 * Errors: as ss_render.
 */
SS_API ss_status ss_render_mesh(const ss_mesh *m, const unsigned char *vertex_rgb, const unsigned char *face_rgb,
                                const ss_render_options *o, unsigned char *rgb, ss_error *err);

/* The scale (pixels per world unit) at which `m`, seen from o's view, fills o's image minus margins.
 * The smallest over several meshes shows them all at one common scale (set it as o->scale).
 *
 * Inputs:
 *   m        the mesh
 *   o        the options (view, size, margin)
 * Returns: the scale; 0 for an empty mesh.
 */
SS_API double ss_render_fit_scale(const ss_mesh *m, const ss_render_options *o);

/* Writes an 8-bit RGB PNG.
 *
 * Inputs:
 *   path     the file
 *   rgb      3·width·height bytes, row-major, top row first
 *   width, height  the size (>= 1)
 * Errors: SS_ERR_INVALID on an empty image; SS_ERR_IO when writing fails; SS_ERR_NOMEM;
 *   SS_ERR_UNSUPPORTED in a build without libpng.
 */
SS_API ss_status ss_write_png(const char *path, const unsigned char *rgb, int width, int height, ss_error *err);

/* ---- colours ---------------------------------------------------------------------------------- */

typedef enum ss_colormap_kind {
  SS_CMAP_VIRIDIS = 0, /* perceptual sequential, dark blue → green → yellow (scalar fields) */
  SS_CMAP_HEAT = 1     /* white → yellow → red → dark red (errors: 0 is white) */
} ss_colormap_kind;

/* Perceptual sequential colormap (viridis-like).
 *
 * Inputs:
 *   t        position, clamped to [0, 1]; NaN maps to 0
 * Outputs:
 *   rgb      the colour
 */
SS_API void ss_colormap(double t, unsigned char rgb[3]);
/* The colour of position t in colormap `kind`.
 *
 * Inputs:
 *   kind     SS_CMAP_VIRIDIS or SS_CMAP_HEAT
 *   t        position, clamped to [0, 1]
 * Outputs:
 *   rgb      the colour
 */
SS_API void ss_colormap_kind_rgb(ss_colormap_kind kind, double t, unsigned char rgb[3]);
/* A distinct colour for a segment label (well separated hues for the first ~20 labels).
 *
 * Inputs:
 *   label    the label (< 0: grey)
 * Outputs:
 *   rgb      the colour
 */
SS_API void ss_label_color(int label, unsigned char rgb[3]);

/* Per-face colours of a segmentation: a face whose three corners share label l gets
 * ss_label_color(l), faces across segments get `neutral` — the paper's convention for boundary
 * triangles.
 *
 * Inputs:
 *   m        the mesh
 *   labels   nv labels (-1 = none)
 *   neutral  NULL (light grey 225,225,220) or the colour of faces across segments
 * Outputs:
 *   face_rgb 3*nf bytes (caller-allocated)
 * Errors: SS_ERR_INVALID on a NULL argument or a face index out of range.
 */
SS_API ss_status ss_segmentation_face_colors(const ss_mesh *m, const int *labels, const unsigned char *neutral,
                                             unsigned char *face_rgb, ss_error *err);
/* Renumbers labels in place so that its segment ids agree with `ref` on the same vertices where
 * they overlap most (greedy on the overlap counts, each reference id used once); segments left without
 * a partner get ids after the reference's largest. Gives corresponding segments of shapes in
 * correspondence (e.g. FAUST poses, identity ground truth) the same colour.
 *
 * Inputs:
 *   labels   n vertex labels (ids >= -1), updated in place
 *   ref      n reference labels of the same vertices
 * Errors: SS_ERR_INVALID on a label below -1 or too many segments to align; SS_ERR_NOMEM.
 */
SS_API ss_status ss_labels_align(int *labels, const int *ref, int n, ss_error *err);

/* ---- 2-D drawing on an RGB image (everything clipped to the image) ------------------------------ */

/* Fills a whole image with one colour.
 *
 * Inputs:
 *   rgb      w x h image (3·w·h bytes), updated
 *   c        the colour
 */
SS_API void ss_image_fill(unsigned char *rgb, int w, int h, const unsigned char c[3]);
/* Copies a sw x sh image into dst with its top-left corner at (x, y), clipped to dst.
 *
 * Inputs:
 *   dst      dw x dh image, updated
 *   src      sw x sh image
 *   x, y     where src's top-left corner goes
 */
SS_API void ss_image_blit(unsigned char *dst, int dw, int dh, const unsigned char *src, int sw, int sh, int x, int y);
/* Fills the rectangle (x, y, rw, rh) with one colour, clipped to the image.
 *
 * Inputs:
 *   rgb      w x h image, updated
 *   x, y, rw, rh  top-left corner and size
 *   c        the colour
 */
SS_API void ss_image_rect(unsigned char *rgb, int w, int h, int x, int y, int rw, int rh, const unsigned char c[3]);
/* Text in a built-in 5x7 pixel font, each font pixel drawn as a scale x scale block, clipped to the
 * image. Covers digits, letters (lower case drawn as upper case), space and
 * . , - + : / % ( ) = _ # < > * [ ] '; other characters are drawn as a box.
 *
 * Inputs:
 *   rgb      w x h image, updated
 *   x, y     top-left corner of the text
 *   scale    font pixel size
 *   c        the colour
 *   text     the text
 * Returns: the width drawn in pixels.
 */
SS_API int ss_draw_text(unsigned char *rgb, int w, int h, int x, int y, int scale, const unsigned char c[3],
                        const char *text);
/* ss_draw_text turned a quarter counter-clockwise (reading upwards, as a y-axis label): the text
 * covers columns x .. x + 7 scale - 1 and rows y - width .. y - 1 (width = ss_text_width).
 *
 * Inputs:
 *   rgb, w, h, scale, c, text  as ss_draw_text
 *   x, y     the bottom-left corner of the turned text
 * Returns: the width (its height on the image).
 */
SS_API int ss_draw_text_up(unsigned char *rgb, int w, int h, int x, int y, int scale, const unsigned char c[3],
                           const char *text);
/* Width in pixels that ss_draw_text takes for a text.
 *
 * Inputs:
 *   text     the text
 *   scale    font pixel size
 * Returns: the width.
 */
SS_API int ss_text_width(const char *text, int scale);
/* A vertical colour bar with its range written beside it: the box (x, y, bw, bh), hi at the top,
 * tick labels lo, mid and hi (printf %.3g) to its right, and an optional title above.
 *
 * Inputs:
 *   rgb      w x h image, updated
 *   x, y, bw, bh  the bar's box
 *   kind     the colormap
 *   lo, hi   the range
 *   title    NULL or a title
 *   text_scale  font pixel size
 *   text_rgb the text colour
 */
SS_API void ss_draw_colorbar(unsigned char *rgb, int w, int h, int x, int y, int bw, int bh, ss_colormap_kind kind,
                             double lo, double hi, const char *title, int text_scale, const unsigned char text_rgb[3]);

/* ---- colours of maps and fields (map_colors.c, scalar_colors.c) -------------------------------- */

/* Smooth per-vertex colours from the positions normalised to the bounding box (x → red, y → green,
 * z → blue, each in [0.12, 0.97] of full scale): the "texture" a map transfers.
 *
 * Inputs:
 *   m        the mesh
 * Outputs:
 *   rgb      3*nv bytes (caller-allocated)
 */
SS_API void ss_coordinate_colors(const ss_mesh *m, unsigned char *rgb);
/* ss_coordinate_colors with a smooth 3-D checker pattern darkening half of its cells (cell size
 * period/2 times the bounding-box diagonal): shows where a map shifts or turns a part (e.g. the head)
 * by less than the colour ramps can reveal.
 *
 * Inputs:
 *   m        the mesh
 *   period   <= 0: plain ss_coordinate_colors
 * Outputs:
 *   rgb      3*nv bytes (caller-allocated)
 */
SS_API void ss_coordinate_pattern_colors(const ss_mesh *m, double period, unsigned char *rgb);
/* Colour transfer through a point map (pull-back): out[i] = target_rgb[map[i]].
 *
 * Inputs:
 *   nx       source vertices
 *   map      nx vertices of the target, in [0, ny)
 *   ny       target vertices
 *   target_rgb  3*ny bytes
 * Outputs:
 *   out      3*nx bytes (caller-allocated)
 * Errors: SS_ERR_INVALID on a NULL argument or a map entry outside [0, ny).
 */
SS_API ss_status ss_map_transfer_colors(int nx, const int *map, int ny, const unsigned char *target_rgb, unsigned char *out,
                                        ss_error *err);
/* Per-vertex colours of a field: colormap `kind` over [lo, hi] (clamped); non-finite values grey.
 *
 * Inputs:
 *   v        n values
 *   kind     the colormap
 *   lo, hi   the range
 * Outputs:
 *   rgb      3*n bytes (caller-allocated)
 */
SS_API void ss_scalar_colors(const double *v, int n, ss_colormap_kind kind, double lo, double hi, unsigned char *rgb);

/* ---- panels: several scenes on one image (panels.c) ------------------------------------------- */

/* One cell of a panel grid (ss_render_panels): a scene and its title. */
typedef struct ss_panel {
  ss_render_scene scene; /* scene.mesh NULL: an empty cell */
  const char *title;     /* written under the panel; NULL or "": none */
} ss_panel;

/* How ss_render_panels arranges its panels (start from ss_panel_layout_init). */
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

/* Fills l with the defaults: one row, titles on, common scale on, no colour bar (viridis over
 * [0, 1], centred when enabled), no heading.
 *
 * Outputs:
 *   l        every field written
 */
SS_API void ss_panel_layout_init(ss_panel_layout *l);

/* Renders n panels, o->width x o->height pixels each, row by row into a grid (text scale grows with
 * the panel height), with titles, a colour bar and a heading as l says.
 *
 * Inputs:
 *   panels   n panels (scene.mesh NULL: an empty cell)
 *   o        options of one panel (not NULL)
 *   l        layout (not NULL; start from ss_panel_layout_init)
 * Outputs:
 *   rgb      *rgb: the malloc'd image (free())
 *   width, height  its size
 * Errors: SS_ERR_INVALID on bad sizes or an image beyond 32768 pixels a side or 10^8 pixels;
 *   ss_render's errors for the scenes; SS_ERR_NOMEM.
 */
SS_API ss_status ss_render_panels(const ss_panel *panels, int n, const ss_render_options *o, const ss_panel_layout *l,
                                  unsigned char **rgb, int *width, int *height, ss_error *err);

/* ---- a comparison of point maps X -> Y, as the paper's Figures 9–11 (map_comparison.c) ---------- */

#define SS_MAP_COMPARISON_MAX 4

/* What a map-comparison figure shows. Start from ss_map_comparison_init; maps, errors and means are
 * required, everything else optional (NULL / 0: not drawn).
 */
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

/* Starts a map comparison of X -> Y: everything off, checker_period 0.06.
 *
 * Inputs:
 *   x, y     the two meshes (borrowed)
 * Outputs:
 *   c        every field written
 */
SS_API void ss_map_comparison_init(ss_map_comparison *c, const ss_mesh *x, const ss_mesh *y);

/* A comparison of point maps X -> Y as the paper's Figures 9–11: two rows of o->width x o->height
 * panels at one scale (ss_render_panels): top, Y coloured by its coordinates, then X pulled back
 * through each map (colour transfer), then X's segments; bottom, X pulled back through the ground
 * truth (what a perfect map shows above; an empty cell without gt), each map's error as a heat map on
 * the shared scale with its colour bar beside the row, then Y's segments.
 *
 * Inputs:
 *   c        what to show (above)
 *   o        options of one panel (not NULL)
 * Outputs:
 *   rgb      *rgb: the malloc'd image (free())
 *   width, height  its size
 *   error_max  (may be NULL) the top of the heat scale
 * Errors: SS_ERR_INVALID on a missing map, a map, gt, landmark, label, centre or pair out of range;
 *   ss_render_panels' errors.
 */
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

/* Starts a plot: 1600 x 1000 pixels, ranges [0, 1], automatic ticks, scales 1, legend lower right,
 * grid on, no series, no texts.
 *
 * Outputs:
 *   p        every field written
 */
SS_API void ss_plot_init(ss_plot *p);
/* A colour for series i that stays distinct from its neighbours for the first ~10 (then repeats
 * darker).
 *
 * Inputs:
 *   i        the series index (< 0 taken as 0)
 * Outputs:
 *   rgb      the colour
 */
SS_API void ss_plot_color(int i, unsigned char rgb[3]);
/* Draws a line plot: frame, ticks with labels, grid, anti-aliased curves (each of constant width,
 * its joints without overlaps) clipped to the frame, the legend (a line sample beside each label),
 * title and axis labels.
 *
 * Inputs:
 *   p        the plot
 * Outputs:
 *   rgb      *rgb: a malloc'd 3 x width x height RGB image (free())
 * Errors: SS_ERR_INVALID on sizes outside 64..16384, an empty range, more than SS_PLOT_MAX_SERIES
 *   series or a series without points; SS_ERR_NOMEM.
 */
SS_API ss_status ss_render_plot(const ss_plot *p, unsigned char **rgb, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
