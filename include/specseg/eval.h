/* specseg — reproducing the paper's evaluation (library specseg_eval, above the core and
 * specseg_render): a deterministic PRNG, the pairing policies, FAUST's left–right symmetry map, the
 * results CSV (read / merge / aggregate), the Table 1 runner (prepared shapes cached, OpenMP over
 * work units, resumable, shardable), §5 coherency runs and the paper's figures. This is the library
 * that knows the data sets' layout (FAUST as DATA/faust/tr_reg_NNN.off). */
#ifndef SPECSEG_EVALUATION_H
#define SPECSEG_EVALUATION_H

#include <stdint.h>
#include <stdio.h>

#include "specseg/core.h"
#include "specseg/render.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Deterministic PRNG: splitmix64 (same stream on every machine and compiler) -------------- */

/* State of the deterministic splitmix64 generator. */
typedef struct ss_rng {
  uint64_t state;
} ss_rng;

/* Seeds the generator.
 *
 * Inputs:
 *   seed     any value (the same seed gives the same stream on every machine)
 * Outputs:
 *   r        the state
 */
SS_API void ss_rng_seed(ss_rng *r, uint64_t seed);
/* The next 64-bit value of the splitmix64 stream.
 *
 * Inputs:
 *   r        the state (advanced)
 * Returns: the value.
 */
SS_API uint64_t ss_rng_next(ss_rng *r);
/* Uniform integer in [0, n), without modulo bias (rejection sampling).
 *
 * Inputs:
 *   r        the state (advanced)
 *   n        the bound
 * Returns: the value; 0 when n <= 1 (the state is then not advanced).
 */
SS_API int ss_rng_below(ss_rng *r, int n);

/* ---- Pairing policies (paper §6.1) ------------------------------------------------------------ */

typedef enum ss_pair_policy {
  SS_POLICY_RANDOM = 0, /* any two different shapes */
  SS_POLICY_SUBJ = 1,   /* same subject, different pose */
  SS_POLICY_POSE = 2    /* same pose, different subjects */
} ss_pair_policy;

/* Name of a pairing policy.
 *
 * Inputs:
 *   p        the policy
 * Returns: "random", "subj" or "pose" (static); "?" out of range.
 */
SS_API const char *ss_pair_policy_name(ss_pair_policy p); /* "random" | "subj" | "pose" */
/* The policy of a name (inverse of ss_pair_policy_name).
 *
 * Inputs:
 *   s        "random", "subj" or "pose" (NULL allowed)
 * Returns: the policy; -1 when unknown.
 */
SS_API int ss_pair_policy_parse(const char *s);            /* -1 when unknown */

/* npairs distinct ordered pairs (x, y), x ≠ y, drawn without replacement from all pairs the policy
 * allows, deterministically from `seed`. Shape s is subject s / nposes, pose s % nposes (FAUST:
 * tr_reg_NNN, 10 × 10).
 *
 * Inputs:
 *   policy   the pairing policy (§6.1)
 *   nsubjects, nposes  the data set's layout
 *   npairs   pairs wanted
 *   seed     the PRNG seed
 * Outputs:
 *   x, y     npairs shape indices each (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes or when fewer than npairs pairs exist; SS_ERR_NOMEM.
 */
SS_API ss_status ss_eval_pairs(ss_pair_policy policy, int nsubjects, int nposes, int npairs, uint64_t seed, int *x,
                               int *y, ss_error *err);

/* ---- Left–right symmetry map ------------------------------------------------------------------ */

/* How ss_symmetry_map's plane fit and map came out. */
typedef struct ss_symmetry_stats {
  double normal[3], point[3]; /* the fitted mirror plane */
  double involution;          /* fraction of x with sym[sym[x]] == x */
  double mean_residual;       /* mean |reflect(x) − sym(x)| / bbox diagonal */
  int refined;                /* vertices whose nearest-reflection candidate the intrinsic check changed */
} ss_symmetry_stats;

/* Left–right symmetry map of an (approximately) mirror-symmetric shape: sym[x] = mirror vertex of x.
 * Steps: (1) a plane with normal Σ (p(lm) − p(lm_mirror)) through the centroid; (2) ICP refinement of
 * the plane (reflect, nearest vertices, refit normal = principal direction of x − sym(x), point = mean
 * midpoint), 10 rounds; (3) intrinsic check: among the 8 vertices nearest to the reflected point, keep
 * the one whose exact geodesic distances to the landmarks best match x's distances to the mirrored
 * landmarks (all scaled by 1/√area), with the Euclidean offset as a tie-breaker.
 *
 * Inputs:
 *   m        the mesh, nv vertices
 *   nl       landmark pairs
 *   lm, lm_mirror  nl vertices each: lm_mirror[i] is the mirror of lm[i] (equal for landmarks on the
 *            symmetry plane, e.g. the head); at least one pair must differ
 * Outputs:
 *   sym      nv vertices (caller-allocated)
 *   stats    (may be NULL) the fitted plane and quality figures
 * Errors: SS_ERR_INVALID on bad arguments, landmarks out of range or all on the plane; SS_ERR_NUMERIC;
 *   errors of the geodesic fields; SS_ERR_NOMEM.
 */
SS_API ss_status ss_symmetry_map(const ss_mesh *m, int nl, const int *lm, const int *lm_mirror, int *sym,
                                 ss_symmetry_stats *stats, ss_error *err);

/* ---- Results: one row per (scenario, method, pair) -------------------------------------------- */

/* SS_LM_NONE: landmark-free (issue 16): the segments paired by ss_pair_centres_auto, the paired
 * centres as the landmarks of STD / ASA / DIFF; needs 100 eigenpairs (the runner then computes
 * max(k, 100) per shape, so rows of the other sets in the same run may differ from a run without
 * "none" in the last digits). */
typedef enum ss_lm_set { SS_LM_BEST = 0, SS_LM_GT = 1, SS_LM_FPS = 2, SS_LM_NONE = 3 } ss_lm_set;
/* STD / ASA / DIFF: the paper's maps (ss_match_paper_options); REFINED: the library's default output
 * (ss_match_default_options with the run's k: refined, selected by its unsupervised energy) */
typedef enum ss_eval_method { SS_METHOD_STD = 0, SS_METHOD_ASA = 1, SS_METHOD_DIFF = 2, SS_METHOD_REFINED = 3 } ss_eval_method;
#define SS_EVAL_NMETHODS 4
/* Name of a landmark set.
 *
 * Inputs:
 *   s        the set
 * Returns: "best", "gt", "fps" or "none" (static); "?" out of range.
 */
SS_API const char *ss_lm_set_name(ss_lm_set s);           /* "best" | "gt" | "fps" | "none" */
/* Name of an evaluation method.
 *
 * Inputs:
 *   m        the method
 * Returns: "std", "asa", "diff" or "refined" (static); "?" out of range.
 */
SS_API const char *ss_eval_method_name(ss_eval_method m); /* "std" | "asa" | "diff" | "refined" */
/* The landmark set of a name (inverse of ss_lm_set_name).
 *
 * Inputs:
 *   s        the name (NULL allowed)
 * Returns: the set; -1 when unknown.
 */
SS_API int ss_lm_set_parse(const char *s);
/* The method of a name (inverse of ss_eval_method_name).
 *
 * Inputs:
 *   s        the name (NULL allowed)
 * Returns: the method; -1 when unknown.
 */
SS_API int ss_eval_method_parse(const char *s);

/* One row of a Table 1 results CSV: the errors of one method on one pair. */
typedef struct ss_eval_row {
  ss_pair_policy policy;
  ss_lm_set landmarks;
  ss_eval_method method;
  int x, y;                      /* shape indices */
  double error, error_sym;       /* mean geodesic error / √area(Y), plain and symmetric */
  int segments_x, segments_y, paired;
  double seconds;                /* matching time of this row (wall) */
  int samples;                   /* vertices the error averages over */
  double cpu_seconds;            /* CPU time of the matching (its thread; BLAS runs single-threaded) */
  /* landmark-free rows: 2 every segment pair right (a pair (cx, cy) is right when vertex cx of X,
   * the ground truth being the identity, lies in segment cy of Y), 1 every pair right after the
   * left-right symmetry map (the mirror), 0 otherwise; -1 for the other rows (CSV column "pairing",
   * optional when read: -1 when absent) */
  int pairing;
} ss_eval_row;

/* The results CSV's header line (no newline).
 *
 * Returns: a static string.
 */
SS_API const char *ss_eval_csv_header(void);
/* One row of the results CSV (no newline), %.17g for reals, so CSV → read → CSV is exact.
 *
 * Inputs:
 *   r        the row
 *   size     bytes at buf
 * Outputs:
 *   buf      the line (truncated to size - 1 bytes)
 */
SS_API void ss_eval_csv_format_row(const ss_eval_row *r, char *buf, size_t size);
/* Reads a results CSV (header required; columns found by name, unknown extra ones ignored). A
 * truncated last line (interrupted run) is dropped silently.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   rows     *rows: malloc'd (free())
 *   nrows    their count
 * Errors: SS_ERR_IO for a missing or unreadable file; SS_ERR_PARSE "PATH:LINE: what" for any other
 *   malformed line; SS_ERR_NOMEM.
 */
SS_API ss_status ss_eval_csv_read(const char *path, ss_eval_row **rows, int *nrows, ss_error *err);
/* Sorts rows into canonical order (policy, landmarks, method, x, y) and removes duplicates; rows
 * with the same key must agree.
 *
 * Inputs:
 *   rows     n rows, updated in place
 *   n        updated to the count kept
 * Errors: SS_ERR_INVALID when two rows of one key disagree (naming the key); SS_ERR_NOMEM.
 */
SS_API ss_status ss_eval_rows_canonical(ss_eval_row *rows, int *n, ss_error *err);

/* Table 1 layout: 12 rows (FAUST {best,gt,fps}, subj ×3, pose ×3, sym ×3) × 4 methods (the paper's
 * three, then the refined default). The sym rows average error_sym of the random-policy rows. Means
 * are summed in canonical row order, so any split of the rows into shards gives bit-identical means.
 */
typedef struct ss_table1 {
  double mean[12][SS_EVAL_NMETHODS];
  int count[12][SS_EVAL_NMETHODS];
} ss_table1;
/* Table 1's means and counts from result rows (landmark-free rows left out: ss_table1_none_aggregate).
 *
 * Inputs:
 *   rows     n rows, any order (a sorted copy is made)
 * Outputs:
 *   t        zeroed, then the means and counts
 * Errors: as ss_eval_rows_canonical.
 */
SS_API ss_status ss_table1_aggregate(const ss_eval_row *rows, int n, ss_table1 *t, ss_error *err);
/* The paper's Table 1 values, same rows, its three methods. */
SS_API extern const double ss_table1_paper[12][3];
SS_API extern const char *const ss_table1_row_names[12];

/* The landmark-free rows beside Table 1: policies random / subj / pose and the sym variant of the
 * random rows (rows 0..3) x methods, and per policy the fraction of shape pairs whose pairing was
 * entirely right (all_right) and right up to the mirror (mirror_right, which includes all_right),
 * over the paper methods' rows (a refined row carries no pairing: NaN when there are only those). */
typedef struct ss_table1_none {
  double mean[4][SS_EVAL_NMETHODS];
  int count[4][SS_EVAL_NMETHODS];
  double all_right[3], mirror_right[3];
  int pairs[3];
} ss_table1_none;
/* The landmark-free rows beside Table 1 (ss_table1_none above) from result rows.
 *
 * Inputs:
 *   rows     n rows, any order (a sorted copy is made)
 * Outputs:
 *   t        zeroed, then the means, counts and pairing fractions
 * Errors: as ss_eval_rows_canonical.
 */
SS_API ss_status ss_table1_none_aggregate(const ss_eval_row *rows, int n, ss_table1_none *t, ss_error *err);

/* ---- Manifests: Table 1 on any data set (manifest.c; format in docs/evaluation.md, "Any data
 * set") ------------------------------------------------------------------------------------------- */

/* how the pairs of a group are chosen */
typedef enum ss_manifest_pairs {
  SS_MANIFEST_PAIRS_ALL = 0,    /* every ordered pair of distinct meshes of the group (default) */
  SS_MANIFEST_PAIRS_RANDOM = 1, /* n of those, drawn without replacement from the group's seed */
  SS_MANIFEST_PAIRS_FIRST = 2,  /* the reference mesh to every other mesh of the group */
  SS_MANIFEST_PAIRS_LISTED = 3  /* only the group's `pair A B` lines */
} ss_manifest_pairs;

/* One mesh of a manifest. */
typedef struct ss_manifest_mesh {
  char *name;      /* unique in the manifest (default: the file name without folder and extension) */
  char *path;      /* the mesh file, resolved against the manifest's folder */
  char *landmarks; /* its own landmark file (resolved; NULL: none) */
  char *symmetry;  /* its own left-right symmetry map (resolved; NULL: the group's, if any) */
  int group;
} ss_manifest_mesh;

/* A group of a manifest: meshes in correspondence, their ground truth, landmarks and pairs. */
typedef struct ss_manifest_group {
  char *name;
  int first, count;       /* its meshes: first .. first + count - 1 (manifest order) */
  int gt_maps;            /* 0: ground truth = identity (equal vertex counts); 1: per-pair map files */
  int reference;          /* manifest index of the FPS reference (default the group's first mesh) */
  int fps_seed;           /* vertex of the reference the FPS starts from (default 0) */
  char *landmarks;        /* one landmark file valid on every mesh (identity only; NULL: none) */
  char *symmetry;         /* one symmetry map valid on every mesh (identity only; NULL: none) */
  ss_manifest_pairs pairs;
  int random_n;           /* SS_MANIFEST_PAIRS_RANDOM */
  uint64_t random_seed;
} ss_manifest_group;

/* A ground-truth map file of a manifest. */
typedef struct ss_manifest_map {
  int x, y;   /* manifest indices: the ground truth x -> y (line i = image on y of vertex i of x) */
  char *path; /* resolved */
} ss_manifest_map;

/* A manifest as ss_manifest_read read it (free with ss_manifest_free). */
typedef struct ss_manifest {
  int nmeshes, ngroups, nmaps;
  ss_manifest_mesh *meshes;
  ss_manifest_group *groups;
  ss_manifest_map *maps;     /* sorted by (x, y) */
  int npairs, *px, *py;      /* the ordered pairs to run (manifest indices), group by group */
} ss_manifest;

/* Reads and checks a manifest (syntax, names, groups, pairs; every pair of a `gt maps` group must
 * have its map line). Files it names are not opened here: the runner reads them. Format:
 * docs/evaluation.md.
 *
 * Inputs:
 *   path     the manifest file (its folder resolves relative paths)
 * Outputs:
 *   m        the manifest (free with ss_manifest_free)
 * Errors: SS_ERR_IO for an unreadable file; SS_ERR_PARSE "PATH:LINE: what" for a malformed line;
 *   SS_ERR_NOMEM.
 */
SS_API ss_status ss_manifest_read(const char *path, ss_manifest *m, ss_error *err);
/* ss_manifest_read of len bytes of text in memory.
 *
 * Inputs:
 *   text, len  the manifest text
 *   name     stands for PATH in messages
 *   base_dir the folder relative paths are resolved against
 * Outputs:
 *   m        the manifest (free with ss_manifest_free)
 * Errors: SS_ERR_PARSE "NAME:LINE: what"; SS_ERR_NOMEM.
 */
SS_API ss_status ss_manifest_read_memory(const char *text, size_t len, const char *name, const char *base_dir,
                                         ss_manifest *m, ss_error *err);
/* Frees everything m holds and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   m        from ss_manifest_read / ss_manifest_read_memory
 */
SS_API void ss_manifest_free(ss_manifest *m);
/* Manifest index of a mesh name.
 *
 * Inputs:
 *   m        the manifest
 *   name     the name
 * Returns: the index; -1 when absent.
 */
SS_API int ss_manifest_find(const ss_manifest *m, const char *name);
/* The ground-truth map file of the pair x -> y.
 *
 * Inputs:
 *   m        the manifest
 *   x, y     manifest indices
 * Returns: the resolved path (owned by m); NULL for identity ground truth or no such line.
 */
SS_API const char *ss_manifest_map_path(const ss_manifest *m, int x, int y);

/* Per group, landmark set and method: mean error (and symmetric error) over the rows whose pair lies
 * in the group (rows summed in canonical order, as ss_table1_aggregate).
 *
 * Inputs:
 *   m        the manifest
 *   rows     n rows, any order
 * Outputs:
 *   mean, mean_sym, count  ngroups x 4 x SS_EVAL_NMETHODS each (caller-allocated), index
 *            (g * 4 + lmset) * SS_EVAL_NMETHODS + method
 * Errors: SS_ERR_INVALID on rows of pairs outside the manifest (an index beyond it, or two groups) and
 *   as ss_eval_rows_canonical; SS_ERR_NOMEM.
 */
SS_API ss_status ss_manifest_aggregate(const ss_manifest *m, const ss_eval_row *rows, int n, double *mean,
                                       double *mean_sym, int *count, ss_error *err);

/* ---- The Table 1 runner ----------------------------------------------------------------------- */

/* Progress of ss_table1_run, passed to its progress callback. */
typedef struct ss_table1_progress {
  int shapes_done, shapes_total; /* shape preparation (first phase) */
  long rows_done, rows_total;    /* rows computed (second phase) */
  double seconds;                /* since the phase began (wall) */
} ss_table1_progress;
typedef void (*ss_table1_progress_fn)(void *user, const ss_table1_progress *p);
typedef void (*ss_table1_log_fn)(void *user, const char *line);

/* Options of ss_table1_run (start from ss_table1_default_options). */
typedef struct ss_table1_options {
  const char *data_dir;   /* folder with faust/tr_reg_NNN.off and faust/landmarks_best.txt */
  /* a data set of one's own instead of FAUST (NULL: FAUST under data_dir). Its pairs replace the
   * policies (rows have policy "random", x / y = manifest indices; npairs is not used); landmark sets:
   * best = the manifest's landmark files, gt = FPS (Appendix A) on each group's reference carried by
   * the ground truth, fps = each mesh's own FPS from vertex 0, none as for FAUST. Borrowed. */
  const ss_manifest *manifest;
  /* pairing rule of the paper's ASA / DIFF rows: 0 (default) the paper's (its Table 1), 1 the
   * library's confidence rules (ss_pairing_default_options, min_landmarks included) — write such
   * rows to another CSV: the row key does not record the rule */
  int confident_pairing;
  const char *out_csv;    /* results file: rows already there are skipped (resume); new rows appended */
  const char *cache_dir;  /* NULL: in-memory only; else per-shape preparation cached there, one file
                             per shape with its key (library version, input mesh hash, options) and
                             a 64-bit FNV-1a checksum */
  int npairs;             /* per policy (default 100) */
  uint64_t seed;          /* default 1 */
  int jobs;               /* parallel work units (OpenMP threads); 0 = omp default */
  int shard_i, shard_n;   /* run the shard_i-th (0-based) of shard_n slices; default 0 / 1 */
  int error_samples;      /* 0 (default): exact mean over all vertices (~0.1 s per good map, ~1.5 s for
                             the FPS rows' bad maps); else a faster estimate from this many random
                             vertices plus their mirrors — a different seeded sample for each target
                             shape, whose exact fields are computed once per target (64 gave -29%..+12%
                             per row against the exact mean) */
  int k;                  /* eigenpairs of the functional map basis (default 50) */
  /* bit sets of what to run: policies default to all (7), landmark sets to best, gt, fps (7; | 1 <<
   * SS_LM_NONE adds the landmark-free rows), methods to the paper's STD / ASA / DIFF (7); 1 <<
   * SS_METHOD_REFINED adds the refined default, whose shapes carry their own max(k, descr_k,
   * zoomout_kmax) eigenpairs (kept in the same cache entry) */
  int policies_mask, lm_mask, methods_mask;
  /* Progress and messages go to the caller (the library prints nothing). Both may be NULL (the
   * default); they are called one at a time (from whichever worker thread), with `user`. */
  ss_table1_progress_fn progress; /* after each prepared shape and each finished row */
  ss_table1_log_fn log;           /* one line per stage (no newline), and one for every cache entry found
                                     damaged (checksum, length) or written for another key (version,
                                     mesh, options): such an entry is never used, it is recomputed and
                                     rewritten */
  void *user;
} ss_table1_options;

/* Fills o with the defaults: 100 pairs per policy, seed 1, shard 0 of 1, exact errors, k 50, all
 * policies, landmark sets best / gt / fps, methods STD / ASA / DIFF; no paths, no callbacks.
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_table1_default_options(ss_table1_options *o);

/* Runs (the shard of) Table 1: prepares the shapes (through cache_dir when set), matches the pairs
 * of every selected policy, landmark set and method, and appends one row per result to o->out_csv
 * (rows already in the file are skipped: resume).
 *
 * Inputs:
 *   o        options (data_dir or manifest, and out_csv, required)
 * Outputs:
 *   new_rows the number of rows computed now
 * Errors: SS_ERR_INVALID on missing paths, an empty manifest or bad options; SS_ERR_IO when the CSV
 *   cannot be written; SS_ERR_PARSE on a bad landmark file or CSV; errors of the shape preparation
 *   and matching; SS_ERR_NOMEM.
 */
SS_API ss_status ss_table1_run(const ss_table1_options *o, int *new_rows, ss_error *err);

/* ---- §5 coherency and timings ----------------------------------------------------------------- */

/* The §5 coherency of one set of shapes, with and without streamlining. */
typedef struct ss_coherency_result {
  char name[64];       /* "faust" or a TOSCA class */
  int nshapes;
  double coherency[2]; /* mean over Y ≠ X0: [0] with streamlining, [1] without */
  double min_coherency[2];
  int hist[2][32];     /* segment counts (31 = 31 or more) over all shapes of the set */
} ss_coherency_result;

/* Coherency (§5) of every shape of a set with the set's first shape (ground truth = identity: all
 * shapes share connectivity), with and without streamlining, and the segment counts.
 *
 * Inputs:
 *   name     the set's name (copied into res)
 *   n        number of shapes (>= 2)
 *   paths    n mesh files
 *   jobs     OpenMP threads (0: the default)
 * Outputs:
 *   res      the result
 * Errors: SS_ERR_INVALID on bad arguments or meshes of unequal vertex counts; errors of ss_read_mesh
 *   and ss_segment; SS_ERR_NOMEM.
 */
SS_API ss_status ss_eval_coherency_set(const char *name, int n, const char *const *paths, int jobs,
                                       ss_coherency_result *res, ss_error *err);

/* ---- Pictures: the paper's Figures 3 and 9–11 ------------------------------------------------- */

/* Figure 3: segmentations of FAUST tr_reg_000 .. tr_reg_<count-1> (ss_segment, default options),
 * segment ids aligned to tr_reg_000's (ss_labels_align), boundary triangles neutral, centres as black
 * spheres, 5 panels a row at one common scale, written to a PNG.
 *
 * Inputs:
 *   data_dir the folder with faust/tr_reg_NNN.off
 *   count    number of shapes
 *   o        one panel's options (size, view)
 *   png      the output file
 * Outputs:
 *   segments (may be NULL) count segment counts
 * Errors: SS_ERR_INVALID on bad arguments; errors of ss_read_mesh, ss_segment, ss_render_panels and
 *   ss_write_png; SS_ERR_NOMEM.
 */
SS_API ss_status ss_eval_faust_gallery(const char *data_dir, int count, const ss_render_options *o, const char *png,
                                       int *segments, ss_error *err);

/* What ss_eval_map_figure drew: the pair, its errors and its segment pairing. */
typedef struct ss_map_figure {
  int x, y;                /* the pair tr_reg_x -> tr_reg_y */
  ss_lm_set lmset;         /* and its landmark set */
  double mean_error[3];    /* STD, ASA, DIFF: mean exact geodesic error / sqrt(area(Y)) over all vertices */
  double error_scale;      /* top of the shared heat scale (errors above it are saturated) */
  int paired, segments_x, segments_y;
  int paired_right;        /* pairs the ground truth confirms (most of X's segment maps into Y's) */
  int width, height;       /* of the PNG */
} ss_map_figure;

/* Figures 9–11: the pair x -> y matched with STD, ASA and DIFF exactly as the Table 1 rows are
 * (per-shape preparation through cache_dir when not NULL, landmark set lmset — GT from `seed` as the
 * runner draws it —, basis size k), drawn by ss_render_map_comparison in 5 x 2 panels; landmarks
 * white, segment centres black.
 *
 * Inputs:
 *   data_dir, cache_dir  the FAUST folder and the preparation cache (NULL: none)
 *   seed, k, lmset  as the Table 1 runner
 *   x, y     the pair (tr_reg_x -> tr_reg_y)
 *   o        one panel's options
 *   png      the output file
 * Outputs:
 *   info     (may be NULL) the figure's numbers
 * Errors: SS_ERR_INVALID on bad arguments; errors of reading, preparing, matching and rendering;
 *   SS_ERR_NOMEM.
 */
SS_API ss_status ss_eval_map_figure(const char *data_dir, const char *cache_dir, uint64_t seed, int k, ss_lm_set lmset, int x,
                                    int y, const ss_render_options *o, const char *png, ss_map_figure *info, ss_error *err);

/* The showcase pair of a map figure, by a rule fixed before looking at any result: the first ncand
 * pairs the policy draws under seed (ss_eval_pairs, as Table 1 draws them), each matched with STD,
 * ASA and DIFF at landmark set lmset as the Table 1 rows are (exact all-vertex errors); its score is
 * the mean of the three methods' mean errors, and the pair whose score is the median — the
 * ((ncand + 1) / 2)-th smallest, ties in draw order — is the showcase: a typical pair of the row,
 * neither its best nor its worst. ncand = 1: the first pair, unscored.
 *
 * Inputs:
 *   data_dir, cache_dir, seed, k, lmset  as ss_eval_map_figure
 *   policy   the pairing policy
 *   ncand    candidates, 1..100
 * Outputs:
 *   x, y     the pair
 *   index    (may be NULL) its place in the draw
 *   xs, ys, scores  (ncand each, may be NULL) every candidate in draw order (scores 0 when ncand = 1)
 * Errors: SS_ERR_INVALID on bad arguments; errors of ss_eval_pairs, preparing and matching;
 *   SS_ERR_NOMEM.
 */
SS_API ss_status ss_eval_showcase_pair(const char *data_dir, const char *cache_dir, uint64_t seed, int k, ss_lm_set lmset,
                                       ss_pair_policy policy, int ncand, int *x, int *y, int *index, int *xs, int *ys,
                                       double *scores, ss_error *err);

/* ---- The field's benchmarks: a folder of meshes with ground-truth points (benchmark*.c) --------
 * The layout of the remeshed FAUST_r / TOSCA_r (the BCICP data set): meshes NAME.off (any format
 * ss_read_mesh reads) in DIR, or in DIR/vtx_5k, DIR/off or DIR/shapes; per mesh NAME its ground-truth
 * points corres/NAME.vts beside the meshes (or DIR/corres): one 1-based vertex index a line, line k
 * the same point on every shape; optionally corres/NAME.sym.vts, line k the left-right mirror of point
 * k on NAME. Pairs: a pairs file (two names a line, tab or blank separated, '#' comments), else
 * DIR/test_pairs.txt (or one beside the meshes), else every ordered pair of distinct shapes.
 *
 * Protocol (as the field reports it), for a map X -> Y (line i = vertex of Y for vertex i of X,
 * 0-based) and every point k < K = min(points of X, points of Y):
 *   e_k = d_Y(map[vts_X[k] - 1], vts_Y[k] - 1) / sqrt(area(Y)),
 * d_Y the exact (VTP) geodesic distance on Y, computed by ss_map_geodesic_error as `specseg error`
 * computes it (so a pair's mean equals `specseg error` on the K-line files map[vts_X - 1] and
 * vts_Y - 1); the symmetric error e'_k = min(d_Y(m_k, vts_Y[k] - 1), d_Y(m_k, sym_Y[k] - 1)) /
 * sqrt(area(Y)) over the points k < min(K, points of sym_Y) (the map may send X onto Y's mirror
 * image); a pair's mean and median over its points; x 100 as printed. */

/* the cumulative curve's grid: e_j = SS_BENCH_CURVE_MAX * j / (SS_BENCH_CURVE_N - 1), j = 0..250 */
#define SS_BENCH_CURVE_N 251
#define SS_BENCH_CURVE_MAX 0.25
#define SS_BENCH_NAME 96  /* longest shape or class name + 1 */
#define SS_BENCH_METHOD 48 /* longest method name + 1 */

/* One shape of a benchmark folder: its name and files. */
typedef struct ss_benchmark_shape {
  char *name;      /* the mesh file's name without folder and extension */
  char *mesh;      /* its path; NULL: a name the pair list gives without a mesh file */
  char *vts, *sym; /* corres/NAME.vts and corres/NAME.sym.vts when present, else NULL */
} ss_benchmark_shape;

/* A benchmark folder as ss_benchmark_open found it: shapes, folders and pairs. Free with
 * ss_benchmark_set_free.
 */
typedef struct ss_benchmark_set {
  char *dir;         /* the folder given */
  char *mesh_dir;    /* the folder of the meshes (dir, or its vtx_5k/, off/ or shapes/) */
  char *corres_dir;  /* the folder of the .vts files (NULL: none found) */
  char *pairs_file;  /* the pairs' file (NULL: every ordered pair) */
  int nshapes;
  ss_benchmark_shape *shapes; /* sorted by name, numbers in names by value (cat2 < cat10) */
  int nall;          /* pairs listed (or all ordered pairs) before sampling */
  int npairs;
  int *px, *py;      /* npairs pairs X -> Y (shape indices), in the list's order */
} ss_benchmark_set;

/* Opens a benchmark folder (layout above).
 *
 * Inputs:
 *   dir      the folder
 *   pairs_file  the pairs (NULL: dir's test_pairs.txt, else all ordered pairs). A line naming a shape
 *            without a mesh file adds that name as a shape with mesh NULL (its pairs are skipped when run)
 *   max_pairs  0 = every pair; N > 0: N of them drawn without replacement (ss_rng from seed), kept in
 *            the list's order
 *   seed     the PRNG seed
 * Outputs:
 *   b        filled (free with ss_benchmark_set_free); zeroed on failure
 * Errors: SS_ERR_IO (no folder, no mesh in it, an unreadable pairs file); SS_ERR_PARSE "FILE:LINE:
 *   what" (a line without two names, a pair X X); SS_ERR_INVALID on bad arguments; SS_ERR_NOMEM.
 */
SS_API ss_status ss_benchmark_open(const char *dir, const char *pairs_file, int max_pairs, uint64_t seed,
                                   ss_benchmark_set *b, ss_error *err);
/* Frees everything b holds and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   b        from ss_benchmark_open
 */
SS_API void ss_benchmark_set_free(ss_benchmark_set *b);
/* The class of a shape name: the name without its trailing digits ("tr_reg_" for tr_reg_017, "cat"
 * for cat10); a name of digits only is its own class.
 *
 * Inputs:
 *   name     the shape name
 *   n        bytes at cls
 * Outputs:
 *   cls      the class (truncated to n - 1 bytes)
 */
SS_API void ss_benchmark_class(const char *name, char *cls, size_t n);
/* The class of a pair: the class of X when Y's is the same, else "CLASSX/CLASSY".
 *
 * Inputs:
 *   x, y     the shape names
 *   n        bytes at cls
 * Outputs:
 *   cls      the class (truncated to n - 1 bytes)
 */
SS_API void ss_benchmark_pair_class(const char *x, const char *y, char *cls, size_t n);

/* One method's result on one pair: a row of pairs.csv. */
typedef struct ss_benchmark_row {
  char method[SS_BENCH_METHOD];
  char x[SS_BENCH_NAME], y[SS_BENCH_NAME];
  int ok;            /* 1: scored; 0: skipped (why: notes) */
  int points;        /* ground-truth points scored (K) */
  double mean, median; /* of e_k (NAN when skipped) */
  double sym_mean;   /* of e'_k (NAN: no sym.vts for Y) */
  int sym_points;
  double seconds;    /* the method's time for the pair (NAN: not known, e.g. a maps folder) */
  int confident;     /* 1 / 0 the method's own confidence (specseg's landmark-free pairing); -1 unknown */
  char notes[480];   /* warnings and notes, '; ' separated ("" none) */
  int cum[SS_BENCH_CURVE_N]; /* points with e_k <= e_j */
} ss_benchmark_row;

/* pairs.csv: the header line (no newline) and one row (reals %.17g, notes quoted, cum as blank
 * separated counts), at most SS_BENCH_CSV_LINE bytes. */
#define SS_BENCH_CSV_LINE 4096
/* pairs.csv's header line (no newline).
 *
 * Returns: a static string.
 */
SS_API const char *ss_benchmark_csv_header(void);
/* One row of pairs.csv (no newline): reals %.17g, notes quoted, cum as blank separated counts; at
 * most SS_BENCH_CSV_LINE bytes.
 *
 * Inputs:
 *   r        the row
 *   size     bytes at buf
 * Outputs:
 *   buf      the line
 */
SS_API void ss_benchmark_csv_format_row(const ss_benchmark_row *r, char *buf, size_t size);
/* Reads a pairs.csv. A cut last line (interrupted run) is dropped.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   rows     *rows: malloc'd (free())
 *   n        their count
 * Errors: SS_ERR_IO for a missing or unreadable file; SS_ERR_PARSE "PATH:LINE: what" for another
 *   malformed line; SS_ERR_NOMEM.
 */
SS_API ss_status ss_benchmark_csv_read(const char *path, ss_benchmark_row **rows, int *n, ss_error *err);
/* Sorts rows into canonical order (method, x, y by name) and keeps one row per key: a scored row wins
 * over skipped ones (the last skipped row is kept when none scored); two scored rows of a key must
 * agree (points, mean, median, symmetric mean).
 *
 * Inputs:
 *   rows     n rows, updated in place
 *   n        updated to the count kept
 * Errors: SS_ERR_INVALID when two scored rows of a key disagree (naming the key); SS_ERR_NOMEM.
 */
SS_API ss_status ss_benchmark_rows_canonical(ss_benchmark_row *rows, int *n, ss_error *err);

/* Scores a map X -> Y by the protocol above.
 *
 * Inputs:
 *   Y        the target mesh
 *   nx       vertices of X
 *   map      nx vertices of Y
 *   npoints  K
 *   gx, gy   K 0-based vertices of X and of Y (point k)
 *   gsym     nsym 0-based vertices of Y, the mirror of point k (NULL / nsym 0: no symmetric error;
 *            points k < min(K, nsym) are used)
 * Outputs:
 *   r        points, mean, median, sym_mean, sym_points, cum (the other fields untouched)
 *   errors   (may be NULL) the K errors e_k
 * Errors: SS_ERR_INVALID on a map entry or a point outside its mesh (the message says which); errors of
 *   the geodesics; SS_ERR_NOMEM.
 */
SS_API ss_status ss_benchmark_score(const ss_mesh *Y, int nx, const int *map, int npoints, const int *gx, const int *gy,
                                    const int *gsym, int nsym, ss_benchmark_row *r, double *errors, ss_error *err);

/* A summary over pairs (all of a method's, or one class's). Means x 100. */
typedef struct ss_benchmark_stats {
  int pairs;          /* rows: scored + skipped */
  int scored, skipped;
  double mean;        /* mean of the scored pairs' means, x 100 (NAN: none scored) */
  double median;      /* median of them (the mean of the middle two for an even count), x 100 */
  double above5;      /* % of scored pairs whose mean x 100 > 5 */
  int sym_pairs;      /* scored pairs with a symmetric error */
  double sym_mean;    /* mean of their symmetric means, x 100 (NAN: none) */
  int timed;          /* scored pairs with a time */
  double seconds;     /* mean of those times (NAN: none) */
  int not_confident;  /* scored pairs the method reported as not confident */
} ss_benchmark_stats;

/* One method's summary over the pairs: all of them, per pair class, and its cumulative curve. */
typedef struct ss_benchmark_method {
  char name[SS_BENCH_METHOD];
  ss_benchmark_stats all;
  int nclasses;
  char (*classes)[SS_BENCH_NAME];   /* nclasses pair classes (ss_benchmark_pair_class), sorted */
  ss_benchmark_stats *class_stats;  /* nclasses */
  long points;                      /* ground-truth points of the scored pairs */
  double curve[SS_BENCH_CURVE_N];   /* fraction of those points with e_k <= e_j */
} ss_benchmark_method;

/* Every method's summary (ss_benchmark_summarize). Free with ss_benchmark_summary_free. */
typedef struct ss_benchmark_summary {
  int nmethods;
  ss_benchmark_method *methods; /* methods named "specseg..." first, then by name */
} ss_benchmark_summary;

/* Summarises rows per method and pair class (a canonical copy is made, so any split of the rows into
 * shards gives bit-identical numbers).
 *
 * Inputs:
 *   rows     n rows, any order
 * Outputs:
 *   s        the summary (free with ss_benchmark_summary_free)
 * Errors: as ss_benchmark_rows_canonical; SS_ERR_NOMEM.
 */
SS_API ss_status ss_benchmark_summarize(const ss_benchmark_row *rows, int n, ss_benchmark_summary *s, ss_error *err);
/* Frees everything s holds and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   s        from ss_benchmark_summarize
 */
SS_API void ss_benchmark_summary_free(ss_benchmark_summary *s);
/* The summary as JSON text: {"title", "pairs_listed" (when >= 0), "methods": [{"method", "pairs",
 * "scored", "skipped", "mean_x100", "median_x100", "above5_percent", "sym_pairs", "sym_mean_x100",
 * "timed", "seconds_mean", "not_confident", "points", "classes": [{"class", the same numbers}],
 * "curve": {"error": [e_j], "fraction": [...]}}], "warnings": [...]}; reals %.17g, null for NAN.
 *
 * Inputs:
 *   s        the summary
 *   title    (may be NULL) the title
 *   pairs_listed  pairs of the set (< 0: left out)
 *   nwarnings, warnings  (warnings may be NULL) lines to list
 * Outputs:
 *   json     *json: malloc'd text (free())
 * Errors: SS_ERR_INVALID on bad arguments; SS_ERR_NOMEM.
 */
SS_API ss_status ss_benchmark_summary_json(const ss_benchmark_summary *s, const char *title, int pairs_listed, int nwarnings,
                                           const char *const *warnings, char **json, ss_error *err);
/* curves.png: every method's cumulative curve (fraction of its ground-truth points with error <= e,
 * e from 0 to SS_BENCH_CURVE_MAX), labelled with its mean x 100, title above.
 *
 * Inputs:
 *   s        the summary
 *   title    (may be NULL) the title
 *   path     the PNG file
 *   width, height  pixels (<= 0: 1600 x 1000)
 * Errors: those of ss_render_plot and ss_write_png.
 */
SS_API ss_status ss_benchmark_curves_png(const ss_benchmark_summary *s, const char *title, const char *path, int width,
                                         int height, ss_error *err);
/* Writes summary.json and curves.png into out_dir from rows (ss_benchmark_summarize,
 * ss_benchmark_summary_json, ss_benchmark_curves_png).
 *
 * Inputs:
 *   out_dir  the folder
 *   rows     n rows
 *   title, pairs_listed, nwarnings, warnings  as ss_benchmark_summary_json
 * Outputs:
 *   s        the summary (free with ss_benchmark_summary_free)
 *   json     (may be NULL) *json: the JSON text, malloc'd (free())
 * Errors: SS_ERR_INVALID on bad arguments; SS_ERR_IO when a file cannot be written; errors of the
 *   calls above; SS_ERR_NOMEM.
 */
SS_API ss_status ss_benchmark_write_outputs(const char *out_dir, const ss_benchmark_row *rows, int n, const char *title,
                                            int pairs_listed, int nwarnings, const char *const *warnings,
                                            ss_benchmark_summary *s, char **json, ss_error *err);

/* ---- The benchmark runner ---------------------------------------------------------------------- */

/* Progress of ss_benchmark_run, passed to its progress callback. */
typedef struct ss_benchmark_progress {
  int shapes_done, shapes_total; /* reading and preparing shapes (first phase) */
  int pairs_done, pairs_total;   /* pairs scored (second phase) */
  double seconds;                /* since the phase began (wall) */
} ss_benchmark_progress;

/* Options of ss_benchmark_run (start from ss_benchmark_default_options). */
typedef struct ss_benchmark_options {
  const char *dir;        /* the benchmark folder (ss_benchmark_open) */
  const char *pairs_file; /* NULL: the folder's test_pairs.txt, else all ordered pairs */
  int max_pairs;          /* 0: all; N: N sampled from seed */
  uint64_t seed;          /* default 1 */
  int match;              /* 1 (default): specseg's own map per pair, written to OUT/maps/X__Y.txt */
  /* 0 (default): landmark-free (ss_match_prepared_shapes with nl = 0, the defaults: what `specseg
   * match X Y` gives); N > 0: N ground-truth points as landmarks, chosen by Euclidean farthest-point
   * sampling over the points of the set's first shape (by name, of those whose mesh and points read)
   * from its point 0; a pair uses those of them it has (k < K) */
  int landmarks;
  /* external methods: nmaps (name, folder) pairs; a pair's map is DIR/X__Y.txt or DIR/X__Y.npy, line
   * i = vertex of Y for vertex i of X (0-based). Names: letters, digits, '_', '-', '.' */
  int nmaps;
  const char *const *map_names, *const *map_dirs;
  const char *out_dir;    /* pairs.csv (also the resume state: its scored rows are not recomputed),
                             maps/ (ours) */
  const char *cache_dir;  /* NULL: prepared shapes in memory only; else DIR/NAME_<key>.sss
                             (ss_prepared_shape files keyed by the mesh's hash and the eigenpairs; one
                             whose mesh differs or that is damaged is recomputed and rewritten) */
  int jobs;               /* pairs (and shapes) at once; 0: the OpenMP default */
  int shard_i, shard_n;   /* the shard_i-th (0-based) of shard_n contiguous slices of the pairs */
  /* messages go to the caller (the library prints nothing); any may be NULL. Called one at a time. */
  void (*progress)(void *user, const ss_benchmark_progress *p);
  void (*log)(void *user, const char *line);  /* stage lines */
  void (*warn)(void *user, const char *line); /* a file skipped or used in part, once per file */
  void *user;
} ss_benchmark_options;

/* Fills o with the defaults: all pairs, seed 1, our own maps on (match 1), landmark-free, no external
 * maps, shard 0 of 1, no paths, no callbacks.
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_benchmark_default_options(ss_benchmark_options *o);
/* The method name of our own maps under o.
 *
 * Inputs:
 *   o        the options (NULL: landmark-free)
 *   n        bytes at name
 * Outputs:
 *   name     "specseg" (landmark-free) or "specseg_gtN" (N ground-truth landmarks)
 */
SS_API void ss_benchmark_method_name(const ss_benchmark_options *o, char *name, size_t n);

/* What ss_benchmark_run did: counts and warnings. Free with ss_benchmark_info_free. */
typedef struct ss_benchmark_info {
  int pairs_listed;   /* pairs of the set (after --max-pairs) */
  int pairs_shard;    /* of them in this shard */
  int rows_new;       /* rows computed now */
  int rows_kept;      /* scored rows found in pairs.csv (not recomputed) */
  int rows_same_skip; /* skipped rows found there, retried and skipped again for the same reason (not
                         written again) */
  int shapes_prepared, shapes_cached;
  double seconds;
  int nwarnings;      /* the warnings said through o->warn (malloc'd strings) */
  char **warnings;
  int landmarks[64];  /* --landmarks gt:N: the chosen ground-truth point indices (first min(N, 64)) */
  int nlandmarks;
  char landmark_shape[SS_BENCH_NAME];
} ss_benchmark_info;

/* Runs (the shard of) the benchmark: reads the meshes and points the shard's pairs need, prepares
 * our shapes (o->match; in parallel, through the cache), then per pair (in parallel) our map and every
 * external map, each scored by ss_benchmark_score, one row per (method, pair) appended to
 * OUT/pairs.csv as it finishes (scored rows already there are kept; skipped ones are retried). A mesh
 * or .vts file that is missing or does not read, a map file that is missing, has another line count
 * than X has vertices or a vertex outside Y, a match that fails: the pairs concerned are skipped rows
 * (warned once per file, the reason in notes), the run goes on. Files of points of unequal length: the
 * pair uses the common prefix (warned once per file whose length differs from the most common one). A
 * broken sym.vts: warned, no symmetric error for it.
 *
 * Inputs:
 *   o        options (dir and out_dir required)
 * Outputs:
 *   info     (may be NULL) counts and warnings (free with ss_benchmark_info_free)
 * Errors: ss_benchmark_open's; SS_ERR_INVALID on bad options or OUT/maps written by another method of
 *   ours (--landmarks); SS_ERR_IO / SS_ERR_PARSE on an unusable out_dir or pairs.csv; SS_ERR_NOMEM.
 */
SS_API ss_status ss_benchmark_run(const ss_benchmark_options *o, ss_benchmark_info *info, ss_error *err);
/* Frees the warnings of info and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   info     from ss_benchmark_run
 */
SS_API void ss_benchmark_info_free(ss_benchmark_info *info);

#ifdef __cplusplus
}
#endif
#endif
