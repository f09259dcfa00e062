/* specseg render MESH [MESH2 ...] -o OUT.png [--labels L.txt | --scalar F.txt | --map MAP.txt --target Y |
 *                --error MAP.txt --target Y] [--view V] [--size WxH] [--centers C.txt] [--landmarks LM.txt]
 *                [--isolines N] ...
 * Pictures of segmentations, scalar fields, maps and map errors; several meshes become side-by-side
 * panels, each fitted (--scale fit) or at one scale (common, the default for --map / --error).
 * Per-mesh files (--labels, --scalar, --map, --error, --centers, --landmarks) are given either once
 * (used for every mesh) or once per mesh, in mesh order. A
 * two-column landmark file ("i j", as `specseg match` takes) gives column 1 to the first mesh and
 * column 2 to the second (or to the --target of --map). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "specseg/render.h"

static const char USAGE[] =
    "usage: specseg render MESH [MESH2 ...] -o OUT.png\n"
    "                      [--labels L.txt | --scalar F.txt | --map MAP.txt --target Y |\n"
    "                       --error MAP.txt --target Y [--gt GT.txt] [--sym SYM.txt]]\n"
    "                      [--view front|back|left|right|top|bottom|AZ,EL] [--size WxH] [--centers C.txt]\n"
    "                      [--landmarks LM.txt] [--isolines N] [--range LO,HI] [--cols N]\n"
    "                      [--match-colors REF_LABELS.txt] [--no-titles] [--supersample S]\n"
    "                      [--up auto|x|y|z|-x|-y|-z] [--scale fit|common]\n"
    "\n"
    "Software-rendered PNG (z-buffer, Phong, anti-aliased). Several meshes become panels; per-mesh files\n"
    "(--labels, --scalar, --map, --error, --centers, --landmarks) are given once for all meshes or once\n"
    "per mesh, in mesh order. Without a colouring option, a PLY's own vertex colours are drawn. Prints a\n"
    "summary line (on stderr with -o -) that names the up axis used.\n"
    "\n"
    "  MESH ...            mesh files (OFF, OBJ, PLY, STL, glTF, ...; at most 64)\n"
    "  -o, --output FILE   the PNG (required); - writes it to standard output (not to a terminal)\n"
    "  --labels L.txt      segmentation: one colour per segment, boundary triangles neutral\n"
    "  --scalar F.txt      per-vertex field: viridis colormap and colour bar\n"
    "  --map MAP.txt       colour transfer: the --target coloured by its normalised xyz with a soft 3-D\n"
    "                      checker (as eval --figures), MESH by the colour of its image (MAP line i =\n"
    "                      vertex of Y for vertex i of MESH)\n"
    "  --error MAP.txt     geodesic error d_Y(MAP(x), GT(x)) / sqrt(area Y) on MESH, exact geodesics,\n"
    "                      as a heat map with its colour scale\n"
    "  --target Y          the target mesh of --map / --error\n"
    "  --gt GT.txt         ground truth of --error (default: the identity)\n"
    "  --sym SYM.txt       symmetry map of MESH for the symmetric --error (see specseg error)\n"
    "  --view V            front (default), back, left, right, top, bottom or AZ,EL in degrees (|EL| <= 90)\n"
    "  --size WxH          panel size, 16..8192 each (default 800x800)\n"
    "  --centers C.txt     vertex indices drawn as black spheres\n"
    "  --landmarks LM.txt  vertex indices drawn as white spheres (blue on colormaps); 'i j' lines (as\n"
    "                      specseg match takes) put column 1 on the first mesh and column 2 on the second\n"
    "                      (or on the --map target)\n"
    "  --isolines N        N isolines of --scalar, 0..1000 (default 0)\n"
    "  --range LO,HI       fixes the colour scale of --scalar / --error (default: the data's range; errors\n"
    "                      from 0)\n"
    "  --cols N            panels per row, 1..64 (default: all in one row)\n"
    "  --match-colors REF  permute segment ids to agree with the REF labels (same vertex order)\n"
    "  --no-titles         no panel titles\n"
    "  --supersample S     anti-aliasing factor, 1..4 (default 2)\n"
    "  --up AXIS           the axis drawn upwards: x, y, z, -x, -y, -z, or auto (default): the axis along\n"
    "                      which the meshes' lowest vertices spread widest (feet on a floor), else +z\n"
    "                      unless z is the first mesh's shortest side, else +y (FAUST: y, TOSCA: z)\n"
    "  --scale fit|common  fit: each panel framed on its own mesh; common: one scale for all panels, so\n"
    "                      sizes compare (default: common for --map / --error, else fit)\n"
    "One of the input files may be - (standard input).\n";

#define MAXM 64

enum mode { MODE_PLAIN, MODE_LABELS, MODE_SCALAR, MODE_MAP, MODE_ERROR };

typedef struct list {
  const char *v[MAXM];
  int n;
} list;

static int push(list *l, const char *s) {
  if (l->n >= MAXM) return -1;
  l->v[l->n++] = s;
  return 0;
}
/* The file for mesh i: the single one, or the i-th. */
static const char *pick(const list *l, int i) { return l->n == 0 ? NULL : (l->n == 1 ? l->v[0] : l->v[i]); }

typedef struct panel {
  const char *path;
  ss_mesh mesh;
  unsigned char *vrgb, *frgb;
  double *scalar;   /* scalar field / errors (nv) */
  double *markers;  /* 3*nmarkers */
  unsigned char *mrgb;
  int nmarkers;
  char title[96];
} panel;

static const unsigned char NEUTRAL[3] = {225, 225, 220};   /* boundary triangles */
/* the --map target's checker cells, as ss_map_comparison's default (eval --figures) */
#define CHECKER_PERIOD 0.06
static const unsigned char CENTRE_RGB[3] = {20, 20, 20};
/* landmarks: white on segment colours, blue on colormaps (whose low end is white) */
static const unsigned char LANDMARK_RGB[3] = {250, 250, 250}, LANDMARK_RGB_CMAP[3] = {40, 90, 230};

static void stem(const char *path, char *out, size_t n) {
  const char *b = strrchr(path, '/');
  b = b ? b + 1 : path;
  snprintf(out, n, "%s", b);
  char *dot = strrchr(out, '.');
  if (dot && dot != out) *dot = 0;
}

static const char *up_name(int up) {
  static const char *names[] = {"-z", "-y", "-x", "+y", "+x", "+y", "+z"};
  return up >= -3 && up <= 3 ? names[up + 3] : "?";
}

/* --view: a named view or AZ,EL; 0, or -1 when it is neither */
static int parse_view(const char *s, double *az, double *el) {
  static const struct { const char *name; double az, el; } V[] = {
      {"front", 0, 0}, {"back", 180, 0}, {"left", 90, 0}, {"right", -90, 0}, {"top", 0, 90}, {"bottom", 0, -90}};
  for (size_t i = 0; i < sizeof V / sizeof V[0]; i++)
    if (!strcmp(s, V[i].name)) {
      *az = V[i].az, *el = V[i].el;
      return 0;
    }
  char buf[64];
  snprintf(buf, sizeof buf, "%s", s);
  char *comma = strchr(buf, ',');
  if (!comma) return -1;
  *comma = 0;
  if (cli_parse_double(buf, az) || cli_parse_double(comma + 1, el)) return -1;
  if (!isfinite(*az) || !isfinite(*el) || fabs(*el) > 90) return -1;
  return 0;
}

static int take_view(cli_args *A, const cli_opt *o, const char *v) {
  if (parse_view(v, o->dest, o->dest2))
    return cli_bad(A, "--view needs front, back, left, right, top, bottom or AZ,EL (degrees, |EL| <= 90), not '%s'", v);
  return -1;
}

/* --range LO,HI: finite, LO < HI */
static int take_range(cli_args *A, const cli_opt *o, const char *v) {
  double *lo = o->dest, *hi = o->dest2;
  char buf[128];
  snprintf(buf, sizeof buf, "%s", v);
  char *c = strchr(buf, ',');
  if (!c) return cli_bad(A, "--range needs LO,HI, not '%s'", v);
  *c = 0;
  if (cli_parse_double(buf, lo) || cli_parse_double(c + 1, hi) || !isfinite(*lo) || !isfinite(*hi) || !(*lo < *hi))
    return cli_bad(A, "--range needs finite LO < HI, not '%s'", v);
  return -1;
}

/* the files of an option given once or once per mesh; --labels, --scalar, --map and --error also set
 * the picture's mode (want; MODE_PLAIN: none) */
typedef struct file_opt {
  list *l;
  enum mode *mode, want;
} file_opt;

static int take_file(cli_args *A, const cli_opt *o, const char *v) {
  const file_opt *f = o->dest;
  if (push(f->l, v)) return cli_bad(A, "too many %s files (at most %d)", o->names, MAXM);
  if (f->want != MODE_PLAIN) {
    if (*f->mode != MODE_PLAIN && *f->mode != f->want)
      return cli_bad(A, "--labels, --scalar, --map and --error exclude each other");
    *f->mode = f->want;
  }
  return -1;
}

static int take_mesh(cli_args *A, const cli_opt *o, const char *v) {
  return push(o->dest, v) ? cli_bad(A, "too many meshes (at most %d)", MAXM) : -1;
}

/* Read a label/index file and check its length. */
static int read_ints_n(const char *path, int want, int **out, int *n) {
  ss_error err = {{0}};
  if (cli_read_ints(path, out, n, &err)) return cli_error("%s", err.msg);
  if (want >= 0 && *n != want) {
    int got = *n;
    free(*out);
    *out = NULL;
    return cli_error("%s: %d values, the mesh has %d vertices", cli_in_name(path), got, want);
  }
  return 0;
}

/* Spheres at the n vertices idx of the panel's mesh. */
static int add_marker_list(panel *p, const char *path, const int *idx, int n, const unsigned char rgb[3]) {
  for (int k = 0; k < n; k++)
    if (idx[k] < 0 || idx[k] >= p->mesh.nv)
      return cli_error("%s: vertex %d out of range (%s has %d vertices)", cli_in_name(path), idx[k], cli_in_name(p->path), p->mesh.nv);
  double *M = realloc(p->markers, sizeof(double) * 3 * (size_t)(p->nmarkers + n + 1));
  unsigned char *C = M ? realloc(p->mrgb, 3 * (size_t)(p->nmarkers + n + 1)) : NULL;
  if (M) p->markers = M;
  if (C) p->mrgb = C;
  if (!M || !C) return cli_error("out of memory");
  for (int k = 0; k < n; k++) {
    memcpy(p->markers + 3 * (size_t)(p->nmarkers + k), p->mesh.V + 3 * (size_t)idx[k], 3 * sizeof(double));
    memcpy(p->mrgb + 3 * (size_t)(p->nmarkers + k), rgb, 3);
  }
  p->nmarkers += n;
  return 0;
}

static int add_markers(panel *p, const char *path, const unsigned char rgb[3]) {
  int *idx = NULL, n = 0;
  if (read_ints_n(path, -1, &idx, &n)) return -1;
  int rc = add_marker_list(p, path, idx, n, rgb);
  free(idx);
  return rc;
}

/* Landmarks from a one- or two-column file: column (1 or 2) of it. */
static int add_landmarks(panel *p, const char *path, int column, const unsigned char rgb[3]) {
  int *lx = NULL, *ly = NULL, n = 0;
  ss_error err = {{0}};
  if (cli_read_landmarks(path, &lx, &ly, NULL, &n, NULL, &err)) return cli_error("%s", err.msg);
  int rc = add_marker_list(p, path, column == 2 ? ly : lx, n, rgb);
  free(lx);
  free(ly);
  return rc;
}

/* Columns of a landmark file (1 or 2); 0 after an error message. */
static int landmark_columns(const char *path) {
  int *lx = NULL, *ly = NULL, n = 0, cols = 0;
  ss_error err = {{0}};
  if (cli_read_landmarks(path, &lx, &ly, NULL, &n, &cols, &err)) {
    cli_error("%s", err.msg);
    return 0;
  }
  free(lx);
  free(ly);
  return cols;
}

int cmd_render(int argc, char **argv) {
  list meshes = {0}, labels = {0}, scalars = {0}, maps = {0}, centers = {0}, landmarks = {0};
  const char *out = NULL, *target = NULL, *gt_path = NULL, *sym_path = NULL, *ref_path = NULL;
  enum mode mode = MODE_PLAIN;
  int width = 800, height = 800, isolines = 0, cols = 0, titles = 1, ss = 2, up = 99, common = -1;
  double az = 0, el = 0, rlo = 0, rhi = 0;
  static const int UP[] = {99, SS_UP_X, SS_UP_Y, SS_UP_Z, SS_UP_X, SS_UP_Y, SS_UP_Z, SS_UP_NEG_X, SS_UP_NEG_Y, SS_UP_NEG_Z};
  file_opt F[6] = {{&labels, &mode, MODE_LABELS}, {&scalars, &mode, MODE_SCALAR}, {&maps, &mode, MODE_MAP},
                   {&maps, &mode, MODE_ERROR},    {&centers, &mode, MODE_PLAIN},  {&landmarks, &mode, MODE_PLAIN}};
  const cli_opt opts[] = {
      CLI_OPT_POS_FN("MESH", take_mesh, &meshes),
      CLI_OPT_CALL("--labels", take_file, &F[0], NULL),
      CLI_OPT_CALL("--scalar", take_file, &F[1], NULL),
      CLI_OPT_CALL("--map", take_file, &F[2], NULL),
      CLI_OPT_CALL("--error", take_file, &F[3], NULL),
      CLI_OPT_CALL("--centers", take_file, &F[4], NULL),
      CLI_OPT_CALL("--landmarks", take_file, &F[5], NULL),
      CLI_OPT_STR("-o|--output", &out),
      CLI_OPT_STR("--target", &target),
      CLI_OPT_STR("--gt", &gt_path),
      CLI_OPT_STR("--sym", &sym_path),
      CLI_OPT_STR("--match-colors", &ref_path),
      CLI_OPT_CALL("--view", take_view, &az, &el),
      CLI_OPT_WXH("--size", &width, &height, 16, 8192, "--size needs WxH, each between 16 and 8192, not '%s'"),
      CLI_OPT_INT("--isolines", &isolines, 0, 1000, NULL),
      CLI_OPT_INT("--cols", &cols, 1, MAXM, NULL),
      CLI_OPT_INT("--supersample", &ss, 1, 4, "--supersample needs 1..4, not '%s'"),
      CLI_OPT_CALL("--range", take_range, &rlo, &rhi),
      CLI_OPT_FLAG("--no-titles", &titles, 0),
      CLI_OPT_CHOICE("--up", &up, "auto|x|y|z|+x|+y|+z|-x|-y|-z", UP, "--up needs auto, x, y, z, -x, -y or -z, not '%s'"),
      CLI_OPT_CHOICE("--scale", &common, "fit|common", NULL, "--scale needs fit or common, not '%s'"),
      CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc >= 0) return rc;
  const int have_range = rlo < rhi; /* --range given (its LO < HI) */
  int nm = meshes.n;
  if (nm == 0) return cli_bad(&A, "no mesh given");
  if (!out) return cli_bad(&A, "missing -o OUT.png");
  if ((mode == MODE_MAP || mode == MODE_ERROR) && !target)
    return cli_bad(&A, "--map / --error need --target Y");
  if (target && mode != MODE_MAP && mode != MODE_ERROR) return cli_bad(&A, "--target goes with --map or --error");
  if ((gt_path || sym_path) && mode != MODE_ERROR) return cli_bad(&A, "--gt / --sym go with --error");
  if (ref_path && mode != MODE_LABELS) return cli_bad(&A, "--match-colors goes with --labels");
  const list *all[] = {&labels, &scalars, &maps, &centers, &landmarks};
  const char *names[] = {"--labels", "--scalar", "--map/--error", "--centers", "--landmarks"};
  for (int k = 0; k < 5; k++)
    if (all[k]->n > 1 && all[k]->n != nm)
      return cli_bad(&A, "%s given %d times for %d meshes (give it once or once per mesh)", names[k], all[k]->n, nm);

  /* standard input holds one file */
  int from_stdin = cli_is_std(target) + cli_is_std(gt_path) + cli_is_std(sym_path) + cli_is_std(ref_path);
  for (int k = 0; k < 5; k++) from_stdin += cli_count_std(all[k]->v, all[k]->n);
  from_stdin += cli_count_std(meshes.v, meshes.n);
  if (from_stdin > 1) return cli_bad(&A, "only one input can come from standard input ('-')");
  {
    const char *ins[6 * MAXM + 4], *outs[1] = {out};
    int ni = 0;
    for (int k = 0; k < 5; k++)
      for (int i = 0; i < all[k]->n; i++) ins[ni++] = all[k]->v[i];
    for (int i = 0; i < meshes.n; i++) ins[ni++] = meshes.v[i];
    ins[ni++] = target, ins[ni++] = gt_path, ins[ni++] = sym_path, ins[ni++] = ref_path;
    if (cli_check_outputs(&A, outs, 1, ins, ni) >= 0) return A.rc;
  }
  FILE *report = cli_is_std(out) ? stderr : stdout;

  /* a two-column landmark file: column 1 on the first mesh, column 2 on the second (or the target) */
  int lm_two = 0;
  if (landmarks.n == 1) {
    int c = landmark_columns(landmarks.v[0]);
    if (c == 0) return SS_EXIT_FAIL;
    lm_two = c == 2;
    if (lm_two && mode != MODE_MAP && mode != MODE_ERROR && nm > 2)
      return cli_bad(&A, "%s has two columns (first and second shape) but %d meshes are given",
                     cli_in_name(landmarks.v[0]), nm);
  }
  const unsigned char *lm_rgb = mode == MODE_LABELS || mode == MODE_PLAIN ? LANDMARK_RGB : LANDMARK_RGB_CMAP;

  ss_error err = {{0}};
  rc = SS_EXIT_OK;
  int np = 0, nref = 0, *ints = NULL, *refl = NULL, *gt = NULL, *sym = NULL;
  panel *P = calloc((size_t)nm + 1, sizeof(panel));
  ss_panel *SP = calloc((size_t)nm + 1, sizeof(ss_panel));
  ss_mesh Y = {0};
  unsigned char *canvas = NULL;
  double t0 = ss_time();
  if (!P || !SP) { free(P); free(SP); return cli_error("out of memory"); }
  if (target && cli_read_mesh(target, &Y, &err)) { rc = cli_error("%s", err.msg); goto done; }
  if (mode == MODE_MAP) { /* the target, coloured by its coordinates, is the first panel */
    P[0].path = target;
    if (ss_mesh_copy(&Y, &P[0].mesh, &err)) { rc = cli_error("%s", err.msg); goto done; }
    if (!(P[0].vrgb = malloc(3 * (size_t)Y.nv + 1))) { rc = cli_error("out of memory"); goto done; }
    ss_coordinate_pattern_colors(&Y, CHECKER_PERIOD, P[0].vrgb);
    stem(cli_in_name(target), P[0].title, sizeof P[0].title);
    if (lm_two && add_landmarks(&P[0], landmarks.v[0], 2, LANDMARK_RGB_CMAP)) { rc = SS_EXIT_FAIL; goto done; }
    np = 1;
  }
  if (mode == MODE_ERROR) {
    int n;
    if (gt_path && read_ints_n(gt_path, -1, &gt, &n)) { rc = SS_EXIT_FAIL; goto done; }
    if (sym_path && read_ints_n(sym_path, -1, &sym, &n)) { rc = SS_EXIT_FAIL; goto done; }
  }
  if (ref_path) {
    int n;
    if (read_ints_n(ref_path, -1, &refl, &n)) { rc = SS_EXIT_FAIL; goto done; }
    nref = n;
  }
  double lo = INFINITY, hi = -INFINITY;
  for (int i = 0; i < nm; i++) {
    panel *p = &P[np++];
    p->path = meshes.v[i];
    unsigned char *own = NULL;
    if (cli_read_mesh_colors(p->path, &p->mesh, &own, &err)) { rc = cli_error("%s", err.msg); goto done; }
    if (mode == MODE_PLAIN) p->vrgb = own; /* the file's own colours (PLY), when it has them */
    else free(own);
    int nv = p->mesh.nv, n = 0;
    stem(cli_in_name(p->path), p->title, sizeof p->title);
    if (mode == MODE_LABELS) {
      if (read_ints_n(pick(&labels, i), nv, &ints, &n)) { rc = SS_EXIT_FAIL; goto done; }
      for (int v = 0; v < nv; v++)
        if (ints[v] < -1) { rc = cli_error("%s: line %d: negative label %d", cli_in_name(pick(&labels, i)), v + 1, ints[v]); goto done; }
      if (refl) {
        if (nref != nv) {
          rc = cli_error("%s: %d labels, %s has %d vertices", cli_in_name(ref_path), nref, cli_in_name(p->path), nv);
          goto done;
        }
        if (ss_labels_align(ints, refl, nv, &err)) { rc = cli_error("%s: %s", cli_in_name(ref_path), err.msg); goto done; }
      }
      int nseg = 0;
      for (int v = 0; v < nv; v++)
        if (ints[v] + 1 > nseg) nseg = ints[v] + 1;
      if (!(p->frgb = malloc(3 * (size_t)p->mesh.nf + 1))) { rc = cli_error("out of memory"); goto done; }
      /* as the paper's figures: a triangle takes its segment's colour only when all three corners agree */
      if (ss_segmentation_face_colors(&p->mesh, ints, NEUTRAL, p->frgb, &err)) { rc = cli_error("%s: %s", cli_in_name(p->path), err.msg); goto done; }
      if (titles) {
        size_t len = strlen(p->title);
        snprintf(p->title + len, sizeof p->title - len, " (%d)", nseg);
      }
      free(ints);
      ints = NULL;
    } else if (mode == MODE_SCALAR) {
      if (cli_read_doubles(pick(&scalars, i), &p->scalar, &n, &err)) { rc = cli_error("%s", err.msg); goto done; }
      if (n != nv) { rc = cli_error("%s: %d values, %s has %d vertices", cli_in_name(pick(&scalars, i)), n, cli_in_name(p->path), nv); goto done; }
    } else if (mode == MODE_MAP || mode == MODE_ERROR) {
      const char *mp = pick(&maps, i);
      if (read_ints_n(mp, nv, &ints, &n)) { rc = SS_EXIT_FAIL; goto done; }
      for (int v = 0; v < nv; v++)
        if (ints[v] < 0 || ints[v] >= Y.nv) {
          rc = cli_error("%s: line %d: vertex %d out of range (%s has %d vertices)", cli_in_name(mp), v + 1, ints[v], cli_in_name(target), Y.nv);
          goto done;
        }
      if (mode == MODE_MAP) {
        if (!(p->vrgb = malloc(3 * (size_t)nv + 1))) { rc = cli_error("out of memory"); goto done; }
        if (ss_map_transfer_colors(nv, ints, Y.nv, P[0].vrgb, p->vrgb, &err)) { rc = cli_error("%s: %s", cli_in_name(mp), err.msg); goto done; }
      } else {
        if (!(p->scalar = malloc(sizeof(double) * (size_t)nv + 1))) { rc = cli_error("out of memory"); goto done; }
        double mean = 0;
        if (!gt && nv > Y.nv) {
          rc = cli_error("identity ground truth: %s has %d vertices, %s only %d", cli_in_name(p->path), nv, cli_in_name(target), Y.nv);
          goto done;
        }
        if (ss_map_geodesic_error(&Y, nv, ints, gt, sym, p->scalar, &mean, &err)) {
          rc = cli_error("%s: %s", cli_in_name(mp), err.msg);
          goto done;
        }
        size_t len = strlen(p->title);
        snprintf(p->title + len, sizeof p->title - len, " mean %.4f", mean);
      }
      free(ints);
      ints = NULL;
    }
    if (p->scalar)
      for (int v = 0; v < nv; v++)
        if (isfinite(p->scalar[v])) {
          if (p->scalar[v] < lo) lo = p->scalar[v];
          if (p->scalar[v] > hi) hi = p->scalar[v];
        }
    if (pick(&centers, i) && add_markers(p, pick(&centers, i), CENTRE_RGB)) { rc = SS_EXIT_FAIL; goto done; }
    /* sources of --map / --error are all "the first shape"; otherwise mesh 2 takes column 2 */
    int lm_col = lm_two && mode != MODE_MAP && mode != MODE_ERROR && i == 1 ? 2 : 1;
    if (pick(&landmarks, i) && add_landmarks(p, pick(&landmarks, i), lm_col, lm_rgb)) { rc = SS_EXIT_FAIL; goto done; }
  }
  int bar = mode == MODE_SCALAR || mode == MODE_ERROR;
  if (bar) {
    if (have_range) lo = rlo, hi = rhi;
    if (mode == MODE_ERROR && !have_range) lo = 0; /* errors: the scale starts at a perfect map */
    if (!(lo <= hi)) lo = 0, hi = 1;
    if (!(hi > lo)) hi = lo + 1;
    for (int k = 0; k < np; k++) {
      if (!(P[k].vrgb = malloc(3 * (size_t)P[k].mesh.nv + 1))) { rc = cli_error("out of memory"); goto done; }
      ss_scalar_colors(P[k].scalar, P[k].mesh.nv, mode == MODE_ERROR ? SS_CMAP_HEAT : SS_CMAP_VIRIDIS, lo, hi, P[k].vrgb);
    }
  }

  if (up == 99) { /* auto: one axis for all panels, from the meshes */
    const ss_mesh *all_m[MAXM + 1];
    for (int k = 0; k < np; k++) all_m[k] = &P[k].mesh;
    up = ss_render_guess_up(all_m, np);
  }
  ss_render_options o;
  ss_render_default_options(&o);
  o.width = width, o.height = height, o.azimuth = az, o.elevation = el, o.supersample = ss, o.up = up;
  for (int k = 0; k < np; k++) {
    ss_render_scene *sc = &SP[k].scene;
    ss_render_scene_init(sc, &P[k].mesh);
    sc->vertex_rgb = P[k].vrgb;
    sc->face_rgb = P[k].frgb;
    if (mode == MODE_SCALAR && isolines > 0) {
      sc->scalar = P[k].scalar;
      sc->isolines = isolines;
      sc->scalar_min = lo, sc->scalar_max = hi;
    }
    sc->nmarkers = P[k].nmarkers;
    sc->markers = P[k].markers;
    sc->marker_rgb = P[k].mrgb;
    SP[k].title = P[k].title;
  }
  ss_panel_layout L;
  ss_panel_layout_init(&L);
  /* one scale for all panels where sizes are compared (a map's source and target), else each fitted */
  L.common_scale = common >= 0 ? common : mode == MODE_MAP || mode == MODE_ERROR;
  L.cols = cols;
  L.titles = titles;
  L.colorbar = bar;
  L.bar_kind = mode == MODE_ERROR ? SS_CMAP_HEAT : SS_CMAP_VIRIDIS;
  L.bar_lo = lo, L.bar_hi = hi;
  L.bar_title = mode == MODE_ERROR ? "error" : "";
  int cw, ch;
  double t_render = ss_time();
  if (ss_render_panels(SP, np, &o, &L, &canvas, &cw, &ch, &err)) { rc = cli_error("%s", err.msg); goto done; }
  t_render = ss_time() - t_render;
  if (cli_write_png(out, canvas, (int)cw, (int)ch, &err)) { rc = cli_error("%s", err.msg); goto done; }
  fprintf(report, "%d panel%s %dx%d rendered in %.3f s (total %.3f s), up %s -> %s (%dx%d)\n", np,
          np == 1 ? "" : "s", width, height, t_render, ss_time() - t0, up_name(up), cli_out_name(out), cw, ch);
  if (fflush(report) != 0) rc = cli_error("cannot write to standard output");
done:
  for (int k = 0; k <= nm; k++) {
    ss_mesh_free(&P[k].mesh);
    free(P[k].vrgb); free(P[k].frgb); free(P[k].scalar); free(P[k].markers); free(P[k].mrgb);
  }
  free(P); free(SP); free(ints); free(refl); free(gt); free(sym); free(canvas);
  ss_mesh_free(&Y);
  return rc;
}
