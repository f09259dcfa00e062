/* Exact geodesic field (VTP) per source vs our NPP22-graph Dijkstra on the same mesh, side by side.
 * Meshes: FAUST tr_reg_000 (6,890 v), TOSCA david0 (10k), FAUST subdivided once (27.5k) and twice
 * (110k), TOSCA david0 subdivided twice (160k). Median over several sources; peak RSS (getrusage).
 * Usage: bench_geodesic [DATA_DIR] [--quick]   (reference: VTP authors' C++ code on this machine,
 * 23-35 ms on FAUST, 50-66 ms at 10k, ~0.34 s at 50k, 3.1-3.4 s at 200k) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "specseg/geodesic.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "geodesic/vtp.h"

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof(double), cmp_d);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static double peak_mb(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

static void run(const char *name, const ss_mesh *m, int nsrc) {
  ss_error e;
  double t0 = ss_time();
  ss_geodesic_mesh *gm;
  if (ss_geodesic_mesh_build(m, &gm, &e)) { printf("%s: %s\n", name, e.msg); return; }
  double tbuild = ss_time() - t0;
  ss_graph g;
  if (ss_graph_npp22(m, &g, &e)) { printf("%s: %s\n", name, e.msg); ss_geodesic_mesh_free(gm); return; }
  ss_vtp_ws *ws = ss_vtp_ws_new(m->nv, m->nf);
  double *d = malloc(sizeof(double) * m->nv), *tv = malloc(sizeof(double) * nsrc), *tg = malloc(sizeof(double) * nsrc);
  double wins = 0;
  size_t peakw = 0, peakh = 0;
  for (int k = 0; k < nsrc; k++) {
    int s = (int)(((long long)k * 2654435761LL + 12345) % m->nv);
    double a = ss_time();
    ss_vtp_run(gm, ws, &s, 1, 0, NULL, 0, d, NULL, NULL);
    tv[k] = ss_time() - a;
    ss_vtp_stats st;
    ss_vtp_ws_stats(ws, &st);
    wins += (double)st.windows_propagated / nsrc;
    if (st.peak_windows > peakw) peakw = st.peak_windows;
    if (st.peak_heap > peakh) peakh = st.peak_heap;
    a = ss_time();
    ss_graph_dijkstra(&g, &s, 1, 0, d, NULL, NULL);
    tg[k] = ss_time() - a;
  }
  double mv = median(tv, nsrc), mg = median(tg, nsrc);
  printf("%-22s %8d  exact %9.2f ms  npp22 %7.2f ms  ratio %6.1fx  windows/field %9.0f (%.1f/face)  "
         "build %6.1f ms  work peak %.1f MB  rss %.0f MB\n",
         name, m->nv, mv * 1e3, mg * 1e3, mv / mg, wins, wins / m->nf, tbuild * 1e3,
         (peakw * 48.0 + peakh * 16.0 + m->nv * 13.0 + m->nf * 3 * 20.0) / 1048576.0, peak_mb());
  fflush(stdout);
  free(d); free(tv); free(tg);
  ss_vtp_ws_free(ws);
  ss_graph_free(&g);
  ss_geodesic_mesh_free(gm);
}

int main(int argc, char **argv) {
  const char *dir = SS_DATA_DIR_DEFAULT;
  int quick = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--quick")) quick = 1;
    else dir = argv[i];
  }
  char path[4096];
  ss_mesh faust, david, s1, s2, d2a, d2;
  ss_error e;
  printf("exact geodesic field per source (median), ours vs our NPP22 Dijkstra; VTP authors' code: "
         "23-35 ms @6.9k, 50-66 ms @10k, ~340 ms @50k, 3.1-3.4 s @200k\n");
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", dir);
  if (ss_read_mesh(path, &faust, &e)) { printf("SKIP: %s\n", e.msg); return 0; }
  run("faust tr_reg_000", &faust, 9);
  snprintf(path, sizeof path, "%s/tosca/david0.off", dir);
  if (!ss_read_mesh(path, &david, &e)) {
    run("tosca david0", &david, 9);
  } else {
    printf("SKIP: %s\n", e.msg);
    memset(&david, 0, sizeof david);
  }
  if (ss_mesh_subdivide(&faust, &s1, &e)) { printf("subdivide: %s\n", e.msg); return 1; }
  run("faust x1 subdivided", &s1, 5);
  if (!quick) {
    if (ss_mesh_subdivide(&s1, &s2, &e)) { printf("subdivide: %s\n", e.msg); return 1; }
    run("faust x2 subdivided", &s2, 3);
    ss_mesh_free(&s2);
    if (david.nv && !ss_mesh_subdivide(&david, &d2a, &e) && !ss_mesh_subdivide(&d2a, &d2, &e)) {
      run("david0 x2 subdivided", &d2, 3);
      ss_mesh_free(&d2a);
      ss_mesh_free(&d2);
    }
  }
  ss_mesh_free(&s1);
  ss_mesh_free(&faust);
  ss_mesh_free(&david);
  return 0;
}
