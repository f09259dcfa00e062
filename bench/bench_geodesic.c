/* Exact geodesic field (VTP) per source vs our NPP22-graph Dijkstra on the same mesh, side by side.
 * Meshes: FAUST tr_reg_000 (6,890 v), TOSCA david0 (10k), FAUST subdivided once (27.5k) and twice
 * (110k), TOSCA david0 subdivided twice (160k). Median over several sources; peak RSS (getrusage).
 * First the per-map geodesic-error evaluation (ss_geodesic_pairs over all 6,890 vertices of FAUST).
 * Usage: bench_geodesic [DATA_DIR] [--quick] [--maps: map evaluation only]   (reference: VTP authors' C++ code on this machine,
 * 23-35 ms on FAUST, 50-66 ms at 10k, ~0.34 s at 50k, 3.1-3.4 s at 200k) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <omp.h>

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

/* thread CPU time: the machine is shared, wall times of one thread are inflated by the load */
static double thread_cpu(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void run(const char *name, const ss_mesh *m, int nsrc) {
  ss_error e;
  double t0 = ss_time();
  ss_geodesic_mesh *gm;
  if (ss_geodesic_mesh_build(m, &gm, &e)) { printf("%s: %s\n", name, e.msg); return; }
  double tbuild = ss_time() - t0;
  ss_graph g;
  if (ss_graph_npp22(m, &g, &e)) { printf("%s: %s\n", name, e.msg); ss_geodesic_mesh_free(gm); return; }
  ssi_vtp_ws *ws = ssi_vtp_ws_new(m->nv, m->nf);
  double *d = malloc(sizeof(double) * m->nv), *tv = malloc(sizeof(double) * nsrc), *tg = malloc(sizeof(double) * nsrc);
  double wins = 0;
  size_t peakw = 0, peakh = 0;
  for (int k = 0; k < nsrc; k++) {
    int s = (int)(((long long)k * 2654435761LL + 12345) % m->nv);
    double a = thread_cpu();
    ssi_vtp_run(gm, ws, &s, 1, 0, NULL, 0, d, NULL, NULL);
    tv[k] = thread_cpu() - a;
    ssi_vtp_stats st;
    ssi_vtp_ws_stats(ws, &st);
    wins += (double)st.windows_propagated / nsrc;
    if (st.peak_windows > peakw) peakw = st.peak_windows;
    if (st.peak_heap > peakh) peakh = st.peak_heap;
    a = thread_cpu();
    ss_graph_dijkstra(&g, &s, 1, 0, d, NULL, NULL);
    tg[k] = thread_cpu() - a;
  }
  double mv = median(tv, nsrc), mg = median(tg, nsrc);
  printf("%-22s %8d  exact %9.2f ms  npp22 %7.2f ms  ratio %6.1fx  windows/field %9.0f (%.1f/face)  "
         "build %6.1f ms  work peak %.1f MB  rss %.0f MB\n",
         name, m->nv, mv * 1e3, mg * 1e3, mv / mg, wins, wins / m->nf, tbuild * 1e3,
         (peakw * 48.0 + peakh * 16.0 + m->nv * 13.0 + m->nf * 3 * 20.0) / 1048576.0, peak_mb());
  fflush(stdout);
  free(d); free(tv); free(tg);
  ssi_vtp_ws_free(ws);
  ss_graph_free(&g);
  ss_geodesic_mesh_free(gm);
}

/* ---- per-map geodesic error: d_Y(Pi(x), x) for every vertex x, through ss_geodesic_pairs -------- */
static unsigned long long rng_state = 0x9E3779B97F4A7C15ULL;
static double urand(void) { /* splitmix64 -> [0,1) */
  unsigned long long z = (rng_state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return (double)((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
}

/* (a) each vertex to a random 1-ring neighbour */
static void map_ring(const ss_mesh *m, const ss_graph *ge, int *map) {
  for (int x = 0; x < m->nv; x++) {
    int deg = ge->ptr[x + 1] - ge->ptr[x];
    map[x] = deg ? ge->adj[ge->ptr[x] + (int)(urand() * deg)] : x;
  }
}

/* (b) each vertex to a random vertex at graph distance ~r (0.8r..1.2r), plus a fraction mapped to
 * the nearest vertex of its left-right mirror image (x is FAUST's lateral axis) */
static void map_realistic(const ss_mesh *m, const ss_graph *gn, double r, double far_frac, int *map) {
  int n = m->nv, *ring = malloc(sizeof(int) * n), src;
  double *d = malloc(sizeof(double) * n), cx = 0;
  for (int i = 0; i < n; i++) cx += m->V[3 * i] / n;
  for (int x = 0; x < n; x++) {
    if (urand() < far_frac) {
      double q[3] = {2 * cx - m->V[3 * x], m->V[3 * x + 1], m->V[3 * x + 2]}, best = INFINITY;
      int bi = x;
      for (int j = 0; j < n; j++) {
        const double *p = m->V + 3 * j;
        double dd = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
        if (dd < best) { best = dd; bi = j; }
      }
      map[x] = bi;
      continue;
    }
    src = x;
    ss_graph_dijkstra(gn, &src, 1, 1.2 * r, d, NULL, NULL);
    int k = 0;
    for (int j = 0; j < n; j++)
      if (d[j] >= 0.8 * r && d[j] <= 1.2 * r) ring[k++] = j;
    map[x] = k ? ring[(int)(urand() * k)] : x;
  }
  free(ring); free(d);
}

/* process CPU time (all threads): the machine is shared, so wall times are noisy */
static double cpu_time(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void map_eval(const ss_mesh *m) {
  ss_error e;
  ss_geodesic_mesh *gm;
  ss_graph gn, ge;
  if (ss_geodesic_mesh_build(m, &gm, &e) || ss_graph_npp22(m, &gn, &e) || ss_graph_edges(m, &ge, &e)) { printf("map eval: %s\n", e.msg); return; }
  int n = m->nv;
  double area = 0;
  for (int f = 0; f < m->nf; f++) {
    const double *a = m->V + 3 * m->F[3 * f], *b = m->V + 3 * m->F[3 * f + 1], *c = m->V + 3 * m->F[3 * f + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double cr[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    area += 0.5 * sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
  }
  double sa = sqrt(area);
  int *ident = malloc(sizeof(int) * 3 * n), *maps = malloc(sizeof(int) * 3 * n);
  double *d = malloc(sizeof(double) * 3 * n), *fd = malloc(sizeof(double) * n);
  for (int k = 0; k < 3 * n; k++) ident[k] = k % n;
  const char *names[4] = {"(a) 1-ring step", "(b) 0.03*sqrt(A) + 5% mirrored", "(b') 0.03*sqrt(A), no far", "(c) 3 maps (b) at once"};
  printf("map error on %d vertices (sqrt(area) %.3f): ss_geodesic_pairs(map, identity), all vertices, per map; "
         "'plain' = Dijkstra-ordered front from Pi(x) stopped at x, no A* (sampled, scaled to all vertices)\n", n, sa);
  double c0 = cpu_time(), a0 = ss_time();
  ss_geodesic_landmarks *lm = NULL;
  if (ss_geodesic_landmarks_new(gm, 8, &lm, &e)) { printf("landmarks: %s\n", e.msg); return; }
  printf("  landmark fields (8, once per mesh): wall %.3f s, cpu %.3f s\n", ss_time() - a0, cpu_time() - c0);
  for (int t = 0; t < 4; t++) {
    int nm = t == 3 ? 3 : 1;
    for (int k = 0; k < nm; k++) {
      if (t == 0) map_ring(m, &ge, maps + k * n);
      else map_realistic(m, &gn, 0.03 * sa, t == 2 ? 0 : 0.05, maps + k * n);
    }
    /* plain: a Dijkstra-ordered front from Pi(x) stopped at x (the former ss_geodesic_pairs
     * strategy, without its O(nv) set-up per query), on a sample of vertices */
    ssi_vtp_ws *ws = ssi_vtp_ws_new(n, m->nf);
    int ns = t == 0 ? 2000 : 300;
    double a0 = ss_time(), c0 = cpu_time();
    for (int k = 0; k < ns; k++) {
      int x = (int)(urand() * n), s = maps[x];
      ssi_vtp_run(gm, ws, &s, 1, 0, &x, 1, fd, NULL, NULL);
    }
    double before = (ss_time() - a0) / ns * n * nm, beforec = (cpu_time() - c0) / ns * n * nm;
    ssi_vtp_ws_free(ws);
    double t1, t2, c1, c2;
    omp_set_num_threads(1);
    a0 = ss_time(); c0 = cpu_time();
    ss_geodesic_pairs(gm, &lm, maps, ident, nm * n, d, NULL);
    t1 = ss_time() - a0; c1 = cpu_time() - c0;
    omp_set_num_threads(2);
    a0 = ss_time(); c0 = cpu_time();
    ss_geodesic_pairs(gm, &lm, maps, ident, nm * n, d, NULL);
    t2 = ss_time() - a0; c2 = cpu_time() - c0;
    double mean = 0;
    for (int k = 0; k < nm * n; k++) mean += d[k] / (nm * n * sa);
    /* spot check against full fields */
    double worst = 0;
    for (int k = 0; k < 5; k++) {
      int x = (int)(urand() * n);
      ss_vtp_distances(gm, &x, 1, 0, fd, NULL);
      for (int q = 0; q < nm; q++) worst = fmax(worst, fabs(d[q * n + x] - fd[maps[q * n + x]]) / fmax(fd[maps[q * n + x]], 1e-300));
    }
    printf("  %-31s err %.4f | plain: wall %6.3f s, cpu %6.3f s | pairs 1 thread: wall %6.3f s, cpu %6.3f s | "
           "2 threads: wall %6.3f s, cpu %6.3f s | cpu plain/pairs %4.1fx | vs fields %.0e\n",
           names[t], mean, before / nm, beforec / nm, t1 / nm, c1 / nm, t2 / nm, c2 / nm, beforec / c1, worst);
    fflush(stdout);
  }
  { /* (d) symmetric error of map (b): min(d(Pi(x), x), d(Pi(x), x')), x' the mirror vertex of x */
    int *mir = malloc(sizeof(int) * n), *two = malloc(sizeof(int) * 2 * n);
    double cx = 0;
    for (int i = 0; i < n; i++) cx += m->V[3 * i] / n;
    for (int x = 0; x < n; x++) {
      double q[3] = {2 * cx - m->V[3 * x], m->V[3 * x + 1], m->V[3 * x + 2]}, best = INFINITY;
      for (int j = 0; j < n; j++) {
        const double *p = m->V + 3 * j;
        double dd = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
        if (dd < best) { best = dd; mir[x] = j; }
      }
    }
    map_realistic(m, &gn, 0.03 * sa, 0.05, maps);
    for (int x = 0; x < n; x++) { two[2 * x] = x; two[2 * x + 1] = mir[x]; }
    double a0 = ss_time(), c0 = cpu_time();
    ss_geodesic_nearest_of(gm, &lm, maps, two, 2, n, d, NULL);
    double tn = ss_time() - a0, cn = cpu_time() - c0, mean = 0;
    for (int x = 0; x < n; x++) mean += d[x] / (n * sa);
    /* the same through ss_geodesic_pairs on both pairs (the mirrored one is far), sampled */
    int ns = 300, *ps = malloc(sizeof(int) * 2 * ns), *pt = malloc(sizeof(int) * 2 * ns);
    for (int k = 0; k < ns; k++) {
      int x = (int)(urand() * n);
      ps[2 * k] = ps[2 * k + 1] = maps[x]; pt[2 * k] = x; pt[2 * k + 1] = mir[x];
    }
    c0 = cpu_time();
    ss_geodesic_pairs(gm, &lm, ps, pt, 2 * ns, fd, NULL);
    double cp = (cpu_time() - c0) / ns * n;
    printf("  %-31s err %.4f | ss_geodesic_nearest_of (2 threads): wall %6.3f s, cpu %6.3f s | via pairs on both "
           "(sampled): cpu %6.2f s | ratio %.0fx\n", "(d) sym error of (b)", mean, tn, cn, cp, cp / cn);
    free(mir); free(two); free(ps); free(pt);
  }
  free(ident); free(maps); free(d); free(fd);
  ss_graph_free(&gn); ss_graph_free(&ge);
  ss_geodesic_landmarks_free(lm);
  ss_geodesic_mesh_free(gm);
}

int main(int argc, char **argv) {
  const char *dir = SS_DATA_DIR_DEFAULT;
  int quick = 0, maponly = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--quick")) quick = 1;
    else if (!strcmp(argv[i], "--maps")) maponly = 1;
    else dir = argv[i];
  }
  char path[4096];
  ss_mesh faust, david, s1, s2, d2a, d2;
  ss_error e;
  printf("exact geodesic field per source (median thread CPU time), ours vs our NPP22 Dijkstra; VTP authors' code: "
         "23-35 ms @6.9k, 50-66 ms @10k, ~340 ms @50k, 3.1-3.4 s @200k\n");
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", dir);
  if (ss_read_mesh(path, &faust, &e)) { printf("SKIP: %s\n", e.msg); return 0; }
  map_eval(&faust);
  if (maponly) { ss_mesh_free(&faust); return 0; }
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
