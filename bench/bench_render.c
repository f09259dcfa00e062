/* Rendering benchmark (issue 7): a 1024x1024 picture of FAUST tr_reg_000 (segment-like face colours),
 * the deferred-shading rasteriser (ss_render) against the forward-shading baseline it replaced (the
 * first version of src/render/raster.c, kept below verbatim as `forward_render`), same options, same
 * process, alternating runs. Reports wall and process-CPU median times; run with OMP_NUM_THREADS=1 for
 * single-thread figures (the machine is shared, so the CPU time is the stable number).
 *
 *   bench_render [--data DIR] [--size N] [--reps R] [--supersample S] */
#include "specseg/io.h"
#include "specseg/render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif

static double cpu_time(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}


/* Rotation taking world coordinates to camera coordinates: view direction -z, up +y. */
static void view_rotation_fwd(double az_deg, double el_deg, double R[9]) {
  double a = az_deg * M_PI / 180, e = el_deg * M_PI / 180;
  double ca = cos(a), sa = sin(a), ce = cos(e), se = sin(e);
  /* first rotate about y by -a, then about x by e */
  double Ry[9] = {ca, 0, -sa, 0, 1, 0, sa, 0, ca};
  double Rx[9] = {1, 0, 0, 0, ce, -se, 0, se, ce};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0;
      for (int k = 0; k < 3; k++) s += Rx[3 * i + k] * Ry[3 * k + j];
      R[3 * i + j] = s;
    }
}

static ss_status forward_render(const ss_mesh *m, const unsigned char *vertex_rgb, const unsigned char *face_rgb,
                         const ss_render_options *o, unsigned char *rgb, ss_error *err) {
  int s = o->supersample < 1 ? 1 : (o->supersample > 4 ? 4 : o->supersample);
  if (o->width < 1 || o->height < 1 || o->width > 16384 || o->height > 16384)
    return ss_fail(err, SS_ERR_INVALID, "image size %dx%d outside 1..16384", o->width, o->height);
  int W = o->width * s, H = o->height * s;
  size_t npix = (size_t)W * H;
  float *zbuf = malloc(sizeof(float) * npix);
  float *col = malloc(sizeof(float) * 3 * npix);
  double *P = malloc(sizeof(double) * 3 * (size_t)(m->nv > 0 ? m->nv : 1));
  double *N = calloc(3 * (size_t)(m->nv > 0 ? m->nv : 1), sizeof(double));
  if (!zbuf || !col || !P || !N) {
    free(zbuf); free(col); free(P); free(N);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for a %dx%d render", W, H);
  }
  for (size_t i = 0; i < npix; i++) {
    zbuf[i] = -INFINITY;
    for (int c = 0; c < 3; c++) col[3 * i + c] = o->background[c];
  }
  double R[9];
  view_rotation_fwd(o->azimuth, o->elevation, R);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < m->nv; i++) {
    for (int r = 0; r < 3; r++) {
      double v = R[3 * r] * m->V[3 * i] + R[3 * r + 1] * m->V[3 * i + 1] + R[3 * r + 2] * m->V[3 * i + 2];
      P[3 * i + r] = v;
      if (v < lo[r]) lo[r] = v;
      if (v > hi[r]) hi[r] = v;
    }
  }
  /* area-weighted vertex normals in camera space */
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * f;
    if (t[0] < 0 || t[0] >= m->nv || t[1] < 0 || t[1] >= m->nv || t[2] < 0 || t[2] >= m->nv) {
      free(zbuf); free(col); free(P); free(N);
      return ss_fail(err, SS_ERR_INVALID, "face %d has a vertex index out of range", f);
    }
    const double *a = P + 3 * t[0], *b = P + 3 * t[1], *c = P + 3 * t[2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < 3; d++) N[3 * t[k] + d] += n[d];
  }
  for (int i = 0; i < m->nv; i++) {
    double l = sqrt(N[3 * i] * N[3 * i] + N[3 * i + 1] * N[3 * i + 1] + N[3 * i + 2] * N[3 * i + 2]);
    if (l > 0)
      for (int d = 0; d < 3; d++) N[3 * i + d] /= l;
  }
  /* fit the x/y extent into the image, keeping the aspect ratio */
  double ext = fmax((hi[0] - lo[0]) / W, (hi[1] - lo[1]) / H);
  if (!(ext > 0)) ext = 1.0 / (W < H ? W : H);
  double scale = (1.0 - 2 * o->margin) / ext;
  double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
  for (int i = 0; i < m->nv; i++) {
    P[3 * i] = (P[3 * i] - cx) * scale + 0.5 * W;
    P[3 * i + 1] = 0.5 * H - (P[3 * i + 1] - cy) * scale; /* image rows grow downwards */
  }
  const double L[3] = {0.3, 0.4, 1.0};
  double ln = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * f;
    const double *p0 = P + 3 * t[0], *p1 = P + 3 * t[1], *p2 = P + 3 * t[2];
    double area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
    if (fabs(area) < 1e-12) continue;
    int x0 = (int)floor(fmin(p0[0], fmin(p1[0], p2[0]))), x1 = (int)ceil(fmax(p0[0], fmax(p1[0], p2[0])));
    int y0 = (int)floor(fmin(p0[1], fmin(p1[1], p2[1]))), y1 = (int)ceil(fmax(p0[1], fmax(p1[1], p2[1])));
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > W - 1) x1 = W - 1;
    if (y1 > H - 1) y1 = H - 1;
    float fc[3][3];
    for (int k = 0; k < 3; k++)
      for (int c = 0; c < 3; c++)
        fc[k][c] = face_rgb ? face_rgb[3 * f + c] : (vertex_rgb ? vertex_rgb[3 * t[k] + c] : 200);
    for (int y = y0; y <= y1; y++)
      for (int x = x0; x <= x1; x++) {
        double px = x + 0.5, py = y + 0.5;
        double w0 = ((p1[0] - px) * (p2[1] - py) - (p1[1] - py) * (p2[0] - px)) / area;
        double w1 = ((p2[0] - px) * (p0[1] - py) - (p2[1] - py) * (p0[0] - px)) / area;
        double w2 = 1 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        double z = w0 * p0[2] + w1 * p1[2] + w2 * p2[2];
        size_t idx = (size_t)y * W + x;
        if (z <= zbuf[idx]) continue;
        zbuf[idx] = (float)z;
        double n[3];
        for (int d = 0; d < 3; d++) n[d] = w0 * N[3 * t[0] + d] + w1 * N[3 * t[1] + d] + w2 * N[3 * t[2] + d];
        double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double ndl = nl > 0 ? (n[0] * L[0] + n[1] * L[1] + n[2] * L[2]) / (nl * ln) : 1;
        if (nl > 0 && n[2] < 0) ndl = -ndl; /* two-sided lighting */
        double diff = fabs(ndl);
        /* Blinn-Phong specular with the viewer along +z */
        double h[3] = {L[0] / ln, L[1] / ln, L[2] / ln + 1};
        double hn = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        double ndh = nl > 0 ? fabs(n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / (nl * hn) : 0;
        double spec = 0.25 * pow(ndh, 40);
        double shade = 0.35 + 0.65 * diff;
        for (int c = 0; c < 3; c++) {
          double base = w0 * fc[0][c] + w1 * fc[1][c] + w2 * fc[2][c];
          double v = base * shade + 255 * spec;
          col[3 * idx + c] = (float)(v > 255 ? 255 : v);
        }
      }
  }
  /* box-filter the supersamples down */
  for (int y = 0; y < o->height; y++)
    for (int x = 0; x < o->width; x++)
      for (int c = 0; c < 3; c++) {
        double acc = 0;
        for (int j = 0; j < s; j++)
          for (int i = 0; i < s; i++) acc += col[3 * ((size_t)(y * s + j) * W + (x * s + i)) + c];
        rgb[3 * ((size_t)y * o->width + x) + c] = (unsigned char)lround(acc / (s * s));
      }
  free(zbuf); free(col); free(P); free(N);
  return SS_OK;
}

int main(int argc, char **argv) {
  const char *data = getenv("SS_DATA_DIR") ? getenv("SS_DATA_DIR") : SS_DATA_DIR_DEFAULT;
  int size = 1024, reps = 7, ss = 2;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--data") && i + 1 < argc) data = argv[++i];
    else if (!strcmp(argv[i], "--size") && i + 1 < argc) size = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--supersample") && i + 1 < argc) ss = atoi(argv[++i]);
    else {
      fprintf(stderr, "usage: bench_render [--data DIR] [--size N] [--reps R] [--supersample S]\n");
      return 2;
    }
  }
  if (size < 16 || size > 8192 || reps < 1 || reps > 100) return 2;
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", data);
  ss_mesh m = {0};
  ss_error err = {{0}};
  if (ss_read_mesh(path, &m, &err)) {
    fprintf(stderr, "bench_render: %s\n", err.msg);
    return 1;
  }
  unsigned char *fc = malloc(3 * (size_t)m.nf);
  for (int f = 0; f < m.nf; f++) ss_label_color((int)(4 + 3 * m.V[3 * m.F[3 * f] + 1]), fc + 3 * f);
  ss_render_options o;
  ss_render_default_options(&o);
  o.width = o.height = size;
  o.supersample = ss;
  unsigned char *a = malloc(3 * (size_t)size * size), *b = malloc(3 * (size_t)size * size);
  double *tw[2], *tc[2];
  for (int k = 0; k < 2; k++) tw[k] = malloc(sizeof(double) * reps), tc[k] = malloc(sizeof(double) * reps);
  for (int r = 0; r < reps; r++)
    for (int k = 0; k < 2; k++) {
      double w = ss_time(), c = cpu_time();
      ss_status st = k == 0 ? ss_render_mesh(&m, NULL, fc, &o, a, &err) : forward_render(&m, NULL, fc, &o, b, &err);
      tw[k][r] = ss_time() - w;
      tc[k][r] = cpu_time() - c;
      if (st) {
        fprintf(stderr, "bench_render: %s\n", err.msg);
        return 1;
      }
    }
  long differ = 0;
  for (size_t i = 0; i < 3 * (size_t)size * size; i++) differ += abs((int)a[i] - (int)b[i]) > 8;
  printf("FAUST tr_reg_000 (%d faces), %dx%d, supersample %d, %d runs each (median)\n", m.nf, size, size, ss, reps);
  const char *name[2] = {"ss_render (deferred)", "forward baseline"};
  double med[2][2];
  for (int k = 0; k < 2; k++) {
    qsort(tw[k], reps, sizeof(double), cmp_d);
    qsort(tc[k], reps, sizeof(double), cmp_d);
    med[k][0] = tw[k][reps / 2], med[k][1] = tc[k][reps / 2];
    printf("  %-22s wall %.4f s  cpu %.4f s\n", name[k], med[k][0], med[k][1]);
  }
  printf("  ratio baseline/ours: wall %.2fx  cpu %.2fx; bytes differing by > 8: %.3f%%\n", med[1][0] / med[0][0],
         med[1][1] / med[0][1], 100.0 * differ / (3.0 * size * size));
  for (int k = 0; k < 2; k++) free(tw[k]), free(tc[k]);
  free(a); free(b); free(fc);
  ss_mesh_free(&m);
  return 0;
}
