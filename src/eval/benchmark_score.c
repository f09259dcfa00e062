/* The benchmark's numbers: a map's error on a pair (the field's protocol, exact geodesics through
 * ss_map_geodesic_error as `specseg error` computes them), the summary per method and class, its JSON
 * and the cumulative curves' picture. */
#include "benchmark_internal.h"
#include "util/c_locale.h"
#include "specseg/fmap.h"
#include "specseg/geodesic.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int dbl_cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median_sorted(const double *v, int n) {
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

ss_status ss_benchmark_score(const ss_mesh *Y, int nx, const int *map, int npoints, const int *gx, const int *gy,
                             const int *gsym, int nsym, ss_benchmark_row *r, double *errors, ss_error *err) {
  if (!Y || !map || !gx || !gy || !r || nx < 1) return ss_fail(err, SS_ERR_INVALID, "benchmark score: missing input");
  if (npoints < 1) return ss_fail(err, SS_ERR_INVALID, "benchmark score: no ground-truth points");
  const int ny = Y->nv;
  for (int i = 0; i < nx; i++)
    if (map[i] < 0 || map[i] >= ny)
      return ss_fail(err, SS_ERR_INVALID, "map line %d: vertex %d is not on Y (%d vertices)", i + 1, map[i], ny);
  for (int k = 0; k < npoints; k++) {
    if (gx[k] < 0 || gx[k] >= nx)
      return ss_fail(err, SS_ERR_INVALID, "ground-truth point %d: vertex %d is not on X (%d vertices)", k + 1, gx[k], nx);
    if (gy[k] < 0 || gy[k] >= ny)
      return ss_fail(err, SS_ERR_INVALID, "ground-truth point %d: vertex %d is not on Y (%d vertices)", k + 1, gy[k], ny);
  }
  const int ns = gsym && nsym > 0 ? (nsym < npoints ? nsym : npoints) : 0;
  for (int k = 0; k < ns; k++)
    if (gsym[k] < 0 || gsym[k] >= ny)
      return ss_fail(err, SS_ERR_INVALID, "symmetric point %d: vertex %d is not on Y (%d vertices)", k + 1, gsym[k], ny);
  int *img = malloc(sizeof(int) * (size_t)npoints), *dst = malloc(sizeof(int) * 2 * (size_t)(ns > 0 ? ns : 1));
  double *e = malloc(sizeof(double) * (size_t)npoints), *d = malloc(sizeof(double) * (size_t)(ns > 0 ? ns : 1));
  ss_geodesic_mesh *gm = NULL;
  ss_geodesic_landmarks *acc = NULL;
  ss_status st = SS_OK;
  if (!img || !dst || !e || !d) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark score: out of memory"); goto done; }
  for (int k = 0; k < npoints; k++) img[k] = map[gx[k]];
  /* the K-point map onto Y against the K-point ground truth: `specseg error MAPK Y --gt GTK` */
  double mean;
  if ((st = ss_map_geodesic_error(Y, npoints, img, gy, NULL, e, &mean, err))) goto done;
  r->points = npoints, r->mean = mean;
  if (errors) memcpy(errors, e, sizeof(double) * (size_t)npoints);
  /* the symmetric error: each query stops at the nearer of the point and its mirror */
  r->sym_points = ns, r->sym_mean = NAN;
  if (ns > 0) {
    for (int k = 0; k < ns; k++) dst[2 * k] = gy[k], dst[2 * k + 1] = gsym[k];
    if ((st = ss_geodesic_mesh_build(Y, &gm, err))) goto done;
    if ((st = ss_geodesic_nearest_of(gm, &acc, img, dst, 2, ns, d, err))) goto done;
    double s = 0, scale = 1.0 / sqrt(ss_mesh_area(Y));
    for (int k = 0; k < ns; k++) s += d[k] * scale;
    r->sym_mean = s / ns;
  }
  qsort(e, (size_t)npoints, sizeof *e, dbl_cmp);
  r->median = median_sorted(e, npoints);
  for (int j = 0, k = 0; j < SS_BENCH_CURVE_N; j++) {
    const double t = SS_BENCH_CURVE_MAX * j / (SS_BENCH_CURVE_N - 1);
    while (k < npoints && e[k] <= t) k++;
    r->cum[j] = k;
  }
done:
  ss_geodesic_landmarks_free(acc);
  if (gm) ss_geodesic_mesh_free(gm);
  free(img), free(dst), free(e), free(d);
  return st;
}

/* ---- summary ----------------------------------------------------------------------------------- */

void ss_benchmark_summary_free(ss_benchmark_summary *s) {
  if (!s) return;
  for (int m = 0; m < s->nmethods; m++) free(s->methods[m].classes), free(s->methods[m].class_stats);
  free(s->methods);
  memset(s, 0, sizeof *s);
}

/* stats of rows r[0..n) (canonical order, one method); sel: only rows whose pair class is cls (NULL:
 * all); buf: n doubles of scratch */
static void stats_of(const ss_benchmark_row *r, int n, const char *cls, double *buf, ss_benchmark_stats *s) {
  memset(s, 0, sizeof *s);
  double sum = 0, ssum = 0, tsum = 0;
  int above = 0;
  for (int i = 0; i < n; i++) {
    if (cls) {
      char c[SS_BENCH_NAME];
      ss_benchmark_pair_class(r[i].x, r[i].y, c, sizeof c);
      if (strcmp(c, cls)) continue;
    }
    s->pairs++;
    if (!r[i].ok) { s->skipped++; continue; }
    buf[s->scored++] = r[i].mean;
    sum += r[i].mean;
    above += 100 * r[i].mean > 5;
    if (r[i].sym_points > 0 && isfinite(r[i].sym_mean)) s->sym_pairs++, ssum += r[i].sym_mean;
    if (isfinite(r[i].seconds)) s->timed++, tsum += r[i].seconds;
    s->not_confident += r[i].confident == 0;
  }
  s->mean = s->median = s->above5 = s->sym_mean = s->seconds = NAN;
  if (s->scored) {
    s->mean = 100 * (sum / s->scored);
    qsort(buf, (size_t)s->scored, sizeof *buf, dbl_cmp);
    s->median = 100 * median_sorted(buf, s->scored);
    s->above5 = 100.0 * above / s->scored;
  }
  if (s->sym_pairs) s->sym_mean = 100 * (ssum / s->sym_pairs);
  if (s->timed) s->seconds = tsum / s->timed;
}

static int cls_cmp(const void *a, const void *b) { return bm_name_cmp((const char *)a, (const char *)b); }

ss_status ss_benchmark_summarize(const ss_benchmark_row *rows, int n, ss_benchmark_summary *s, ss_error *err) {
  if (!s) return ss_fail(err, SS_ERR_INVALID, "benchmark summary: no output");
  memset(s, 0, sizeof *s);
  if (n < 0 || (n > 0 && !rows)) return ss_fail(err, SS_ERR_INVALID, "benchmark summary: no rows");
  ss_benchmark_row *r = malloc(sizeof *r * (size_t)(n > 0 ? n : 1));
  double *buf = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
  if (!r || !buf) { free(r), free(buf); return ss_fail(err, SS_ERR_NOMEM, "benchmark summary: out of memory"); }
  if (n) memcpy(r, rows, sizeof *r * (size_t)n);
  ss_status st = ss_benchmark_rows_canonical(r, &n, err);
  if (st) { free(r), free(buf); return st; }
  int nm = 0;
  for (int i = 0; i < n; i++) nm += !i || strcmp(r[i].method, r[i - 1].method);
  s->methods = calloc((size_t)(nm > 0 ? nm : 1), sizeof *s->methods);
  if (!s->methods) { free(r), free(buf); return ss_fail(err, SS_ERR_NOMEM, "benchmark summary: out of memory"); }
  for (int a = 0, b; a < n; a = b) {
    for (b = a + 1; b < n && !strcmp(r[a].method, r[b].method);) b++;
    ss_benchmark_method *M = &s->methods[s->nmethods++];
    snprintf(M->name, sizeof M->name, "%s", r[a].method);
    stats_of(r + a, b - a, NULL, buf, &M->all);
    /* its classes */
    M->classes = malloc(sizeof *M->classes * (size_t)(b - a));
    if (!M->classes) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark summary: out of memory"); break; }
    for (int i = a; i < b; i++) ss_benchmark_pair_class(r[i].x, r[i].y, M->classes[i - a], SS_BENCH_NAME);
    qsort(M->classes, (size_t)(b - a), sizeof *M->classes, cls_cmp);
    int nc = 0;
    for (int i = 0; i < b - a; i++)
      if (!nc || strcmp(M->classes[i], M->classes[nc - 1])) memmove(M->classes[nc++], M->classes[i], SS_BENCH_NAME);
    M->nclasses = nc;
    M->class_stats = malloc(sizeof *M->class_stats * (size_t)nc);
    if (!M->class_stats) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark summary: out of memory"); break; }
    for (int c = 0; c < nc; c++) stats_of(r + a, b - a, M->classes[c], buf, &M->class_stats[c]);
    /* the curve over all its scored points */
    long pts = 0, cum[SS_BENCH_CURVE_N] = {0};
    for (int i = a; i < b; i++) {
      if (!r[i].ok) continue;
      pts += r[i].points;
      for (int j = 0; j < SS_BENCH_CURVE_N; j++) cum[j] += r[i].cum[j];
    }
    M->points = pts;
    for (int j = 0; j < SS_BENCH_CURVE_N; j++) M->curve[j] = pts ? (double)cum[j] / (double)pts : NAN;
  }
  free(r), free(buf);
  if (st) ss_benchmark_summary_free(s);
  return st;
}

/* ---- JSON -------------------------------------------------------------------------------------- */

void bm_json_str(FILE *f, const char *s) {
  fputc('"', f);
  for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
    if (*p == '"' || *p == '\\') fprintf(f, "\\%c", *p);
    else if (*p < 0x20) fprintf(f, "\\u%04x", *p);
    else fputc(*p, f);
  }
  fputc('"', f);
}

void bm_json_num(FILE *f, double v) {
  if (isfinite(v)) ssi_fprintf_c(f, "%.17g", v);
  else fputs("null", f);
}

static void json_stats(FILE *f, const ss_benchmark_stats *s) {
  fprintf(f, "\"pairs\": %d, \"scored\": %d, \"skipped\": %d, \"mean_x100\": ", s->pairs, s->scored, s->skipped);
  bm_json_num(f, s->mean);
  fputs(", \"median_x100\": ", f);
  bm_json_num(f, s->median);
  fputs(", \"above5_percent\": ", f);
  bm_json_num(f, s->above5);
  fprintf(f, ", \"sym_pairs\": %d, \"sym_mean_x100\": ", s->sym_pairs);
  bm_json_num(f, s->sym_mean);
  fprintf(f, ", \"timed\": %d, \"seconds_mean\": ", s->timed);
  bm_json_num(f, s->seconds);
  fprintf(f, ", \"not_confident\": %d", s->not_confident);
}

ss_status ss_benchmark_summary_json(const ss_benchmark_summary *s, const char *title, int pairs_listed, int nwarnings,
                                    const char *const *warnings, char **json, ss_error *err) {
  *json = NULL;
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  if (!f) return ss_fail(err, SS_ERR_NOMEM, "benchmark summary: out of memory");
  fputs("{\"title\": ", f);
  bm_json_str(f, title ? title : "");
  if (pairs_listed >= 0) fprintf(f, ", \"pairs_listed\": %d", pairs_listed);
  fputs(", \"methods\": [", f);
  for (int m = 0; m < s->nmethods; m++) {
    const ss_benchmark_method *M = &s->methods[m];
    fputs(m ? ",\n  {\"method\": " : "\n  {\"method\": ", f);
    bm_json_str(f, M->name);
    fputs(", ", f);
    json_stats(f, &M->all);
    fprintf(f, ", \"points\": %ld,\n   \"classes\": [", M->points);
    for (int c = 0; c < M->nclasses; c++) {
      fputs(c ? ", {\"class\": " : "{\"class\": ", f);
      bm_json_str(f, M->classes[c]);
      fputs(", ", f);
      json_stats(f, &M->class_stats[c]);
      fputc('}', f);
    }
    fputs("],\n   \"curve\": {\"error\": [", f);
    for (int j = 0; j < SS_BENCH_CURVE_N; j++) {
      if (j) fputs(", ", f);
      bm_json_num(f, SS_BENCH_CURVE_MAX * j / (SS_BENCH_CURVE_N - 1));
    }
    fputs("], \"fraction\": [", f);
    for (int j = 0; j < SS_BENCH_CURVE_N; j++) {
      if (j) fputs(", ", f);
      bm_json_num(f, M->curve[j]);
    }
    fputs("]}}", f);
  }
  fputs("],\n \"warnings\": [", f);
  for (int w = 0; w < nwarnings; w++) {
    if (w) fputs(", ", f);
    bm_json_str(f, warnings[w]);
  }
  fputs("]}\n", f);
  if (fclose(f)) { free(buf); return ss_fail(err, SS_ERR_NOMEM, "benchmark summary: out of memory"); }
  *json = buf;
  return SS_OK;
}

/* ---- curves.png -------------------------------------------------------------------------------- */

ss_status ss_benchmark_curves_png(const ss_benchmark_summary *s, const char *title, const char *path, int width, int height,
                                  ss_error *err) {
  ss_plot p;
  ss_plot_init(&p);
  if (width > 0) p.width = width;
  if (height > 0) p.height = height;
  p.xmin = 0, p.xmax = SS_BENCH_CURVE_MAX, p.ymin = 0, p.ymax = 1, p.yscale = 100;
  char tt[256];
  snprintf(tt, sizeof tt, "%s%sCUMULATIVE GEODESIC ERROR", title && *title ? title : "", title && *title ? ": " : "");
  p.title = tt, p.xlabel = "GEODESIC ERROR / SQRT(AREA OF Y)", p.ylabel = "% OF GROUND-TRUTH POINTS";
  ss_plot_series ser[SS_PLOT_MAX_SERIES];
  char labels[SS_PLOT_MAX_SERIES][128];
  double ex[SS_BENCH_CURVE_N];
  for (int j = 0; j < SS_BENCH_CURVE_N; j++) ex[j] = SS_BENCH_CURVE_MAX * j / (SS_BENCH_CURVE_N - 1);
  int ns = 0;
  for (int m = 0; m < s->nmethods && ns < SS_PLOT_MAX_SERIES; m++) {
    const ss_benchmark_method *M = &s->methods[m];
    if (!M->points) continue;
    ssi_snprintf_c(labels[ns], sizeof labels[ns], "%s  MEAN %.2f, %d PAIRS", M->name, M->all.mean, M->all.scored);
    ser[ns].n = SS_BENCH_CURVE_N, ser[ns].x = ex, ser[ns].y = M->curve, ser[ns].label = labels[ns];
    ss_plot_color(ns, ser[ns].rgb);
    ns++;
  }
  p.series = ser, p.nseries = ns;
  unsigned char *rgb = NULL;
  ss_status st = ss_render_plot(&p, &rgb, err);
  if (!st) st = ss_write_png(path, rgb, p.width, p.height, err);
  free(rgb);
  return st;
}

ss_status ss_benchmark_write_outputs(const char *out_dir, const ss_benchmark_row *rows, int n, const char *title,
                                     int pairs_listed, int nwarnings, const char *const *warnings, ss_benchmark_summary *sout,
                                     char **json, ss_error *err) {
  if (json) *json = NULL;
  if (!out_dir) return ss_fail(err, SS_ERR_INVALID, "benchmark: no output folder");
  if (mkdir(out_dir, 0755) && errno != EEXIST) return ss_fail(err, SS_ERR_IO, "%s: cannot create: %s", out_dir, strerror(errno));
  ss_benchmark_summary s;
  ss_status st = ss_benchmark_summarize(rows, n, &s, err);
  if (st) return st;
  char *js = NULL, *path = NULL;
  if ((st = ss_benchmark_summary_json(&s, title, pairs_listed, nwarnings, warnings, &js, err))) goto done;
  path = bm_join(out_dir, "summary.json");
  if (!path) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto done; }
  {
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "wb");
    if (!f) { st = ss_fail(err, SS_ERR_IO, "%s: cannot write: %s", tmp, strerror(errno)); goto done; }
    size_t L = strlen(js);
    int bad = fwrite(js, 1, L, f) != L;
    bad |= fclose(f) != 0;
    if (bad || rename(tmp, path)) {
      remove(tmp);
      st = ss_fail(err, SS_ERR_IO, "%s: write error", path);
      goto done;
    }
  }
  free(path);
  path = bm_join(out_dir, "curves.png");
  if (!path) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto done; }
  st = ss_benchmark_curves_png(&s, title, path, 0, 0, err);
done:
  free(path);
  if (!st && json) *json = js, js = NULL;
  free(js);
  if (!st && sout) *sout = s;
  else ss_benchmark_summary_free(&s);
  return st;
}
