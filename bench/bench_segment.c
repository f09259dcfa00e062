/* Segmentation benchmark (issue 3, paper §5): all FAUST shapes with and without streamlining, with and
 * without the critical-point clean-up; segment-count histogram, mean critical points, coherency with
 * X0 = tr_reg_000, per-stage median times; then TOSCA per class (X0 = the class's file 0).
 *
 *   bench_segment [--data DIR] [--faust N] [--no-tosca] [--no-faust] [--faces F]
 *                 [--configs LIST]   (LIST: comma-separated of s5,s0,r5,r0 = streamline/raw × rings)
 *                 [--stride S] (FAUST shapes 0, S, 2S, ...) [--cmcf-steps N] [--cmcf-dt D]
 *
 * Times are per shape, shapes one after the other. Run with
 * OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 for single-thread figures; cpu_total is the process CPU time
 * per shape (meaningful with one thread). */
#include "specseg/io.h"
#include "specseg/segment.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif

typedef struct {
  int ok, m, nraw, nempty, nv;
  int *labels, *centers;
  double t[9]; /* read smooth remesh(+psi) spectrum critical ivd total(read+segment) segment-only, cpu */
  char msg[1200];
} result;

static const char *STAGE[9] = {"read", "smooth", "remesh", "spectrum", "critical", "ivd", "total", "segment", "cpu_total"};

/* CPU seconds of the process: with one thread per process this is the per-shape single-thread cost,
 * much less sensitive than wall time to other programs competing for the cores. */
static double cpu_time(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static double median(double *v, int n) {
  if (n == 0) return NAN;
  qsort(v, n, sizeof *v, cmp_d);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void run_one(const char *path, const ss_segment_options *o, result *r) {
  memset(r, 0, sizeof *r);
  ss_error err = {{0}};
  ss_mesh m = {0};
  ss_segmentation s = {0};
  double c0 = cpu_time();
  double t0 = ss_time();
  if (ss_read_mesh(path, &m, &err)) {
    snprintf(r->msg, sizeof r->msg, "%.1100s", err.msg);
    return;
  }
  double t1 = ss_time();
  if (ss_segment(&m, o, &s, &err)) {
    snprintf(r->msg, sizeof r->msg, "%.150s: %.1000s", path, err.msg);
    ss_mesh_free(&m);
    return;
  }
  double t2 = ss_time();
  r->ok = 1;
  r->m = s.m;
  r->nraw = s.ncrit_raw;
  r->nempty = s.empty_segments;
  r->nv = s.nv;
  r->labels = s.labels;
  r->centers = s.centers;
  s.labels = s.centers = NULL;
  r->t[0] = t1 - t0;
  r->t[1] = s.t_smooth;
  r->t[2] = s.t_remesh + s.t_psi;
  r->t[3] = s.t_spectrum;
  r->t[4] = s.t_critical;
  r->t[5] = s.t_ivd;
  r->t[6] = t2 - t0;
  r->t[7] = t2 - t1;
  r->t[8] = cpu_time() - c0;
  ss_segmentation_free(&s);
  ss_mesh_free(&m);
}

/* Serial on purpose: ARPACK (inside ss_eigs) keeps state in static variables, so two segmentations
 * must not run at once; one shape at a time also makes the times per-shape single-thread figures. */
static void run_all(char **paths, int n, const ss_segment_options *o, result *res) {
  for (int i = 0; i < n; i++) run_one(paths[i], o, &res[i]);
}

static void free_results(result *r, int n) {
  for (int i = 0; i < n; i++) free(r[i].labels), free(r[i].centers);
}

/* Summary of one configuration over one shape set; X0 = res[0]. */
static void report(const char *title, char **names, result *res, int n, int print_hist, int print_times) {
  int hist[64] = {0}, nok = 0, over = 0;
  double sraw = 0, sm = 0;
  for (int i = 0; i < n; i++) {
    if (!res[i].ok) {
      printf("  FAILED %s: %s\n", names[i], res[i].msg);
      continue;
    }
    nok++;
    sraw += res[i].nraw;
    sm += res[i].m;
    if (res[i].m < 64) hist[res[i].m]++;
    else over++;
  }
  printf("%s: %d/%d shapes segmented; mean critical points %.2f raw, %.2f kept\n", title, nok, n,
         nok ? sraw / nok : 0, nok ? sm / nok : 0);
  if (print_hist) {
    printf("  segment-count histogram:");
    for (int k = 0; k < 64; k++)
      if (hist[k]) printf(" %d:%d", k, hist[k]);
    if (over) printf(" >=64:%d", over);
    printf("\n");
  }
  /* coherency against X0 = res[0] */
  if (res[0].ok && n > 1) {
    double sum = 0, mn = 1;
    int cnt = 0, worst = -1;
    for (int i = 1; i < n; i++) {
      if (!res[i].ok || res[i].nv != res[0].nv) continue;
      double c;
      ss_error err;
      if (ss_coherency(res[0].labels, res[0].nv, res[i].labels, res[i].centers, res[i].m, res[i].nv, NULL, &c, &err)) {
        printf("  coherency %s: %s\n", names[i], err.msg);
        continue;
      }
      sum += c;
      cnt++;
      if (c < mn) mn = c, worst = i;
    }
    if (cnt)
      printf("  coherency vs %s: mean %.4f, min %.4f (%s), over %d shapes\n", names[0], sum / cnt, mn,
             worst >= 0 ? names[worst] : "-", cnt);
  }
  if (print_times && nok) {
    double *v = malloc(sizeof(double) * n);
    printf("  median seconds per shape:");
    for (int s = 0; s < 9; s++) {
      int k = 0;
      for (int i = 0; i < n; i++)
        if (res[i].ok) v[k++] = res[i].t[s];
      printf(" %s %.4f", STAGE[s], median(v, k));
    }
    printf("\n");
    free(v);
  }
}

static void list_not8(char **names, result *res, int n) {
  int first = 1, cnt = 0;
  for (int i = 0; i < n; i++) cnt += res[i].ok && res[i].m != 8;
  if (cnt > 20) return; /* the histogram says it all */
  for (int i = 0; i < n; i++)
    if (res[i].ok && res[i].m != 8) {
      printf("%s %s:%d(raw %d)", first ? "  not 8:" : ",", names[i], res[i].m, res[i].nraw);
      first = 0;
    }
  if (!first) printf("\n");
}

int main(int argc, char **argv) {
  const char *data = getenv("SS_DATA_DIR");
  if (!data) data = SS_DATA_DIR_DEFAULT;
  int nfaust = 100, do_tosca = 1, do_faust = 1, faces = 15000, stride = 1, cmcf_steps = 0;
  double cmcf_dt = 0;
  const char *configs = "s5,s0,r5,r0";
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--data") && i + 1 < argc) data = argv[++i];
    else if (!strcmp(argv[i], "--faust") && i + 1 < argc) nfaust = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--no-tosca")) do_tosca = 0;
    else if (!strcmp(argv[i], "--no-faust")) do_faust = 0;
    else if (!strcmp(argv[i], "--faces") && i + 1 < argc) faces = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--configs") && i + 1 < argc) configs = argv[++i];
    else if (!strcmp(argv[i], "--stride") && i + 1 < argc) stride = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--cmcf-steps") && i + 1 < argc) cmcf_steps = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--cmcf-dt") && i + 1 < argc) cmcf_dt = atof(argv[++i]);
    else {
      fprintf(stderr, "usage: bench_segment [--data DIR] [--faust N] [--no-tosca] [--no-faust] [--faces F] [--configs s5,s0,r5,r0] [--stride S] [--cmcf-steps N] [--cmcf-dt D]\n");
      return 2;
    }
  }
  if (nfaust < 1 || nfaust > 100 || stride < 1) return 2;
  nfaust = (nfaust + stride - 1) / stride;
  setvbuf(stdout, NULL, _IOLBF, 0); /* progress survives a timeout */
  char probe[4096];
  snprintf(probe, sizeof probe, "%s/faust/tr_reg_000.off", data);
  FILE *f = fopen(probe, "rb");
  if (!f) {
    printf("SKIP: no data at %s\n", data);
    return 0;
  }
  fclose(f);
  printf("bench_segment: data %s, target faces %d, CMCF steps %d dt %g (0 = module default)\n", data, faces,
         cmcf_steps, cmcf_dt);

  /* configurations */
  ss_segment_options conf[4];
  const char *cname[4] = {"s5", "s0", "r5", "r0"};
  const char *ctitle[4] = {"streamline, clean-up 5 rings", "streamline, no clean-up", "no streamline, clean-up 5 rings",
                           "no streamline, no clean-up"};
  int use[4];
  for (int c = 0; c < 4; c++) {
    ss_segment_default_options(&conf[c]);
    conf[c].target_faces = faces;
    conf[c].no_streamline = c >= 2;
    conf[c].cleanup_rings = (c % 2 == 0) ? 5 : 0;
    conf[c].cmcf_steps = cmcf_steps;
    conf[c].cmcf_dt = cmcf_dt;
    use[c] = strstr(configs, cname[c]) != NULL;
  }

  if (do_faust) {
    char **paths = malloc(sizeof(char *) * nfaust), **names = malloc(sizeof(char *) * nfaust);
    for (int i = 0; i < nfaust; i++) {
      paths[i] = malloc(4200);
      names[i] = malloc(32);
      snprintf(paths[i], 4200, "%s/faust/tr_reg_%03d.off", data, i * stride);
      snprintf(names[i], 32, "tr_reg_%03d", i * stride);
    }
    result *res = calloc(nfaust, sizeof(result));
    for (int c = 0; c < 4; c++) {
      if (!use[c]) continue;
      double t0 = ss_time();
      run_all(paths, nfaust, &conf[c], res);
      char title[128];
      snprintf(title, sizeof title, "FAUST [%s] %s (%.1f s wall)", cname[c], ctitle[c], ss_time() - t0);
      report(title, names, res, nfaust, 1, 1);
      list_not8(names, res, nfaust);
      int ge = 0;
      for (int i = 0; i < nfaust; i++) ge += res[i].ok && res[i].m == 8;
      printf("  exactly 8 segments: %d/%d\n", ge, nfaust);
      free_results(res, nfaust);
      fflush(stdout);
    }
    free(res);
    for (int i = 0; i < nfaust; i++) free(paths[i]), free(names[i]);
    free(paths), free(names);
  }

  if (do_tosca) {
    static const char *cls[8] = {"cat", "centaur", "david", "dog", "horse", "michael", "victoria", "wolf"};
    for (int c = 0; c < 4; c++) {
      if (!use[c]) continue;
      printf("TOSCA [%s] %s\n", cname[c], ctitle[c]);
      for (int k = 0; k < 8; k++) {
        char *paths[64], *names[64];
        int n = 0;
        for (int idx = 0; idx < 40 && n < 64; idx++) {
          char p[4200];
          snprintf(p, sizeof p, "%s/tosca/%s%d.off", data, cls[k], idx);
          FILE *t = fopen(p, "rb");
          if (!t) continue;
          fclose(t);
          paths[n] = strdup(p);
          names[n] = malloc(64);
          snprintf(names[n], 64, "%s%d", cls[k], idx);
          n++;
        }
        if (!n) {
          printf("  %s: no files\n", cls[k]);
          continue;
        }
        result *res = calloc(n, sizeof(result));
        run_all(paths, n, &conf[c], res);
        char title[128];
        snprintf(title, sizeof title, "  %s (%d shapes, X0 = %s)", cls[k], n, names[0]);
        report(title, names, res, n, 1, 0);
        printf("   counts:");
        for (int i = 0; i < n; i++) printf(" %s:%d", names[i], res[i].ok ? res[i].m : -1);
        printf("\n");
        free_results(res, n);
        free(res);
        for (int i = 0; i < n; i++) free(paths[i]), free(names[i]);
        fflush(stdout);
      }
    }
  }
  return 0;
}
