/* Z-buffer rasteriser with deferred shading: triangles and marker-sphere impostors are first resolved
 * to (depth, primitive id, two barycentric / normal coordinates) per sample, then every visible sample
 * is shaded exactly once (Blinn-Phong headlight, two-sided), isolines are found by comparing the level
 * band of neighbouring samples, and the s×s samples of a pixel are averaged. Shading only what is
 * visible keeps a 1024² FAUST frame far below the cost of forward shading with overdraw. */
#include "specseg/render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

void ss_render_default_options(ss_render_options *o) {
  memset(o, 0, sizeof *o);
  o->width = 800;
  o->height = 800;
  o->azimuth = 0;
  o->elevation = 0;
  o->background[0] = o->background[1] = o->background[2] = 255;
  o->supersample = 2;
  o->margin = 0.05;
  o->scale = 0;
}

void ss_render_scene_init(ss_render_scene *s, const ss_mesh *m) {
  memset(s, 0, sizeof *s);
  s->mesh = m;
  s->isoline_rgb[0] = s->isoline_rgb[1] = s->isoline_rgb[2] = 40;
}

/* Rotation taking world coordinates to camera coordinates: view direction -z, up +y. */
static void view_rotation_y(double az_deg, double el_deg, double R[9]) {
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

/* The rotation turning world axis `up` (ss_up_axis) into +y (see render.h), then the view's. */
static void view_rotation(const ss_render_options *o, double R[9]) {
  static const double U[7][9] = {
      {1, 0, 0, 0, 0, -1, 0, 1, 0},  /* -z: (x, -z, y) */
      {-1, 0, 0, 0, -1, 0, 0, 0, 1}, /* -y: (-x, -y, z) */
      {0, 1, 0, -1, 0, 0, 0, 0, 1},  /* -x: (y, -x, z) */
      {1, 0, 0, 0, 1, 0, 0, 0, 1},   /* default: +y */
      {0, -1, 0, 1, 0, 0, 0, 0, 1},  /* +x: (-y, x, z) */
      {1, 0, 0, 0, 1, 0, 0, 0, 1},   /* +y */
      {1, 0, 0, 0, 0, 1, 0, -1, 0},  /* +z: (x, z, -y) */
  };
  double Rv[9];
  view_rotation_y(o->azimuth, o->elevation, Rv);
  int u = o->up >= -3 && o->up <= 3 ? o->up + 3 : 3;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0;
      for (int k = 0; k < 3; k++) s += Rv[3 * i + k] * U[u][3 * k + j];
      R[3 * i + j] = s;
    }
}

static void rotate(const double R[9], const double *v, double *out) {
  for (int r = 0; r < 3; r++) out[r] = R[3 * r] * v[0] + R[3 * r + 1] * v[1] + R[3 * r + 2] * v[2];
}

/* Camera-space bounding box of the mesh vertices; returns 0 when there are none. */
static int view_bbox(const ss_mesh *m, const double R[9], double lo[3], double hi[3]) {
  for (int r = 0; r < 3; r++) lo[r] = INFINITY, hi[r] = -INFINITY;
  int any = 0;
  for (int i = 0; i < m->nv; i++) {
    double p[3];
    rotate(R, m->V + 3 * (size_t)i, p);
    if (!(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]))) continue;
    any = 1;
    for (int r = 0; r < 3; r++) {
      if (p[r] < lo[r]) lo[r] = p[r];
      if (p[r] > hi[r]) hi[r] = p[r];
    }
  }
  return any;
}

double ss_render_fit_scale(const ss_mesh *m, const ss_render_options *o) {
  double R[9], lo[3], hi[3];
  view_rotation(o, R);
  if (!m || !view_bbox(m, R, lo, hi) || o->width < 1 || o->height < 1) return 0;
  double avail = 1.0 - 2 * o->margin;
  if (avail <= 0.01) avail = 0.01;
  double sx = hi[0] > lo[0] ? avail * o->width / (hi[0] - lo[0]) : INFINITY;
  double sy = hi[1] > lo[1] ? avail * o->height / (hi[1] - lo[1]) : INFINITY;
  double s = fmin(sx, sy);
  return isfinite(s) ? s : avail * (o->width < o->height ? o->width : o->height);
}

/* Per-sample buffers of the deferred pass. */
typedef struct gbuf {
  int W, H;  /* full sample grid */
  int y0;    /* first sample row held (the buffers hold rows y0 .. y0 + rows - 1) */
  float *z;
  int *id;   /* -1 background, >= 0 face, <= -2 marker -(id+2) */
  float *b1, *b2;
} gbuf;

static void raster_triangle(gbuf *g, int f, const double *p0, const double *p1, const double *p2, int ylo, int yhi) {
  double area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
  if (!(fabs(area) > 1e-12)) return;
  double fx0 = fmin(p0[0], fmin(p1[0], p2[0])), fx1 = fmax(p0[0], fmax(p1[0], p2[0]));
  double fy0 = fmin(p0[1], fmin(p1[1], p2[1])), fy1 = fmax(p0[1], fmax(p1[1], p2[1]));
  /* samples sit at pixel centres (x + 0.5): only those inside the float bbox can be covered */
  if (!(fx1 >= 0 && fy1 >= 0 && fx0 <= g->W && fy0 <= g->H)) return; /* also NaN */
  /* clamp before converting to int: far-away or huge coordinates must not overflow the cast */
  fx0 = fmax(fx0, -1), fy0 = fmax(fy0, -1), fx1 = fmin(fx1, g->W + 1), fy1 = fmin(fy1, g->H + 1);
  int x0 = (int)ceil(fx0 - 0.5), x1 = (int)floor(fx1 - 0.5);
  int y0 = (int)ceil(fy0 - 0.5), y1 = (int)floor(fy1 - 0.5);
  if (x0 < 0) x0 = 0;
  if (x1 > g->W - 1) x1 = g->W - 1;
  if (y0 < ylo) y0 = ylo;
  if (y1 > yhi) y1 = yhi;
  if (x0 > x1 || y0 > y1) return;
  double inv = 1.0 / area;
  /* edge functions are affine in (px, py): w0 = a0 px + c0 py + d0 etc. */
  double a0 = -(p2[1] - p1[1]) * inv, c0 = (p2[0] - p1[0]) * inv;
  double d0 = ((p1[0]) * (p2[1]) - (p1[1]) * (p2[0])) * inv;
  double a1 = -(p0[1] - p2[1]) * inv, c1 = (p0[0] - p2[0]) * inv;
  double d1 = ((p2[0]) * (p0[1]) - (p2[1]) * (p0[0])) * inv;
  const double eps = -1e-9; /* shared edges: a sample on an edge belongs to both, the z-test decides */
  for (int y = y0; y <= y1; y++) {
    double py = y + 0.5;
    size_t row = (size_t)(y - g->y0) * g->W;
    for (int x = x0; x <= x1; x++) {
      double px = x + 0.5;
      double w0 = a0 * px + c0 * py + d0, w1 = a1 * px + c1 * py + d1, w2 = 1 - w0 - w1;
      if (w0 < eps || w1 < eps || w2 < eps) continue;
      double z = w0 * p0[2] + w1 * p1[2] + w2 * p2[2];
      size_t idx = row + x;
      if (z <= g->z[idx]) continue;
      g->z[idx] = (float)z;
      g->id[idx] = f;
      g->b1[idx] = (float)w1;
      g->b2[idx] = (float)w2;
    }
  }
}

static void raster_sphere(gbuf *g, int k, const double c[3], double r, double rz, int ylo, int yhi) {
  /* r: radius in samples; rz: radius in depth units */
  if (!(isfinite(c[0]) && isfinite(c[1]) && isfinite(c[2]) && r > 0 && r < 4.0 * (g->W + g->H))) return;
  if (c[0] + r < 0 || c[0] - r > g->W || c[1] + r < 0 || c[1] - r > g->H) return;
  int x0 = (int)ceil(c[0] - r - 0.5), x1 = (int)floor(c[0] + r - 0.5);
  int y0 = (int)ceil(c[1] - r - 0.5), y1 = (int)floor(c[1] + r - 0.5);
  if (x0 < 0) x0 = 0;
  if (x1 > g->W - 1) x1 = g->W - 1;
  if (y0 < ylo) y0 = ylo;
  if (y1 > yhi) y1 = yhi;
  for (int y = y0; y <= y1; y++)
    for (int x = x0; x <= x1; x++) {
      double dx = (x + 0.5 - c[0]) / r, dy = (y + 0.5 - c[1]) / r, d2 = dx * dx + dy * dy;
      if (d2 > 1) continue;
      double z = c[2] + rz * sqrt(1 - d2);
      size_t idx = (size_t)(y - g->y0) * g->W + x;
      if (z <= g->z[idx]) continue;
      g->z[idx] = (float)z;
      g->id[idx] = -(k + 2);
      g->b1[idx] = (float)dx;
      g->b2[idx] = (float)-dy; /* image rows grow downwards, camera y upwards */
    }
}

static double lum_clamp(double v) { return v < 0 ? 0 : (v > 255 ? 255 : v); }

/* Output rows per band: the image is produced band by band with small per-thread buffers (a band of
 * samples plus one apron row above and below for the isoline neighbours), which stay in cache and
 * avoid faulting in full-frame buffers. */
#define BAND_ROWS 16

ss_status ss_render(const ss_render_scene *sc, const ss_render_options *o, unsigned char *rgb, ss_error *err) {
  if (!sc || !sc->mesh || !o || !rgb) return ss_fail(err, SS_ERR_INVALID, "render: NULL argument");
  const ss_mesh *m = sc->mesh;
  int s = o->supersample < 1 ? 1 : (o->supersample > 4 ? 4 : o->supersample);
  if (o->width < 1 || o->height < 1 || o->width > 16384 || o->height > 16384)
    return ss_fail(err, SS_ERR_INVALID, "image size %dx%d outside 1..16384", o->width, o->height);
  if (m->nv < 0 || m->nf < 0 || (m->nv > 0 && !m->V) || (m->nf > 0 && !m->F))
    return ss_fail(err, SS_ERR_INVALID, "render: invalid mesh");
  if (sc->nmarkers < 0 || (sc->nmarkers > 0 && !sc->markers))
    return ss_fail(err, SS_ERR_INVALID, "render: %d markers without positions", sc->nmarkers);
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * (size_t)f;
    if (t[0] < 0 || t[0] >= m->nv || t[1] < 0 || t[1] >= m->nv || t[2] < 0 || t[2] >= m->nv)
      return ss_fail(err, SS_ERR_INVALID, "face %d has a vertex index out of range", f);
  }
  int W = o->width * s, H = o->height * s, BS = BAND_ROWS * s;
  int nb = (o->height + BAND_ROWS - 1) / BAND_ROWS;
  size_t nvb = (size_t)(m->nv > 0 ? m->nv : 1);
  double *P = malloc(sizeof(double) * 3 * nvb);
  double *N = calloc(3 * nvb, sizeof(double));
  double *MP = malloc(sizeof(double) * 3 * (size_t)(sc->nmarkers + 1));
  int *bstart = calloc((size_t)nb + 1, sizeof(int)), *blist = NULL;
  if (!P || !N || !MP || !bstart) {
    free(P); free(N); free(MP); free(bstart);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for a %dx%d render", W, H);
  }
  double R[9];
  view_rotation(o, R);
  double lo[3], hi[3];
  if (!view_bbox(m, R, lo, hi)) lo[0] = lo[1] = lo[2] = hi[0] = hi[1] = hi[2] = 0;
  for (int i = 0; i < m->nv; i++) rotate(R, m->V + 3 * (size_t)i, P + 3 * (size_t)i);
  /* area-weighted vertex normals in camera space */
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * (size_t)f;
    const double *a = P + 3 * (size_t)t[0], *b = P + 3 * (size_t)t[1], *c = P + 3 * (size_t)t[2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < 3; d++) N[3 * (size_t)t[k] + d] += n[d];
  }
  for (int i = 0; i < m->nv; i++) {
    double *n = N + 3 * (size_t)i, l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0)
      for (int d = 0; d < 3; d++) n[d] /= l;
  }
  /* world -> sample coordinates */
  double scale = o->scale > 0 ? o->scale : ss_render_fit_scale(m, o);
  if (!(scale > 0)) scale = 1;
  scale *= s;
  double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
  for (int i = 0; i < m->nv; i++) {
    double *p = P + 3 * (size_t)i;
    p[0] = (p[0] - cx) * scale + 0.5 * W;
    p[1] = 0.5 * H - (p[1] - cy) * scale; /* image rows grow downwards */
  }
  double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                     (hi[2] - lo[2]) * (hi[2] - lo[2]));
  double mrad = sc->marker_radius > 0 ? sc->marker_radius : 0.012 * (diag > 0 ? diag : 1);
  for (int k = 0; k < sc->nmarkers; k++) {
    double *q = MP + 3 * (size_t)k;
    rotate(R, sc->markers + 3 * (size_t)k, q);
    q[0] = (q[0] - cx) * scale + 0.5 * W;
    q[1] = 0.5 * H - (q[1] - cy) * scale;
  }

  /* bucket the faces by band: band b holds sample rows b·BS − 1 .. (b+1)·BS (apron included) */
  for (int pass = 0; pass < 2; pass++) {
    for (int f = 0; f < m->nf; f++) {
      const int *t = m->F + 3 * (size_t)f;
      double y0 = fmin(P[3 * (size_t)t[0] + 1], fmin(P[3 * (size_t)t[1] + 1], P[3 * (size_t)t[2] + 1]));
      double y1 = fmax(P[3 * (size_t)t[0] + 1], fmax(P[3 * (size_t)t[1] + 1], P[3 * (size_t)t[2] + 1]));
      if (!(y1 >= 0 && y0 <= H)) continue; /* also drops NaN coordinates */
      y0 = fmax(y0, -1), y1 = fmin(y1, H + 1);
      int r0 = (int)ceil(y0 - 0.5), r1 = (int)floor(y1 - 0.5);
      if (r0 < 0) r0 = 0;
      if (r1 > H - 1) r1 = H - 1;
      if (r0 > r1) continue;
      int b0 = (r0 - 1) / BS, b1 = (r1 + 1) / BS;
      if (b0 < 0) b0 = 0;
      if (b1 > nb - 1) b1 = nb - 1;
      for (int b = b0; b <= b1; b++) {
        if (pass == 0) bstart[b + 1]++;
        else blist[bstart[b]++] = f;
      }
    }
    if (pass == 0) {
      for (int b = 0; b < nb; b++) bstart[b + 1] += bstart[b];
      blist = malloc(sizeof(int) * ((size_t)bstart[nb] + 1));
      if (!blist) {
        free(P); free(N); free(MP); free(bstart);
        return ss_fail(err, SS_ERR_NOMEM, "out of memory for a %dx%d render", W, H);
      }
    } else {
      for (int b = nb; b > 0; b--) bstart[b] = bstart[b - 1]; /* the fill advanced every start by one band */
      bstart[0] = 0;
    }
  }

  /* isoline levels: the band index floor((φ − min)·(n+1)/(max − min)) of the interpolated field */
  int niso = sc->scalar && sc->isolines > 0 ? sc->isolines : 0;
  double smin = sc->scalar_min, smax = sc->scalar_max;
  if (niso && !(smin < smax)) {
    smin = INFINITY, smax = -INFINITY;
    for (int i = 0; i < m->nv; i++)
      if (isfinite(sc->scalar[i])) {
        if (sc->scalar[i] < smin) smin = sc->scalar[i];
        if (sc->scalar[i] > smax) smax = sc->scalar[i];
      }
    if (!(smin < smax)) niso = 0;
  }
  double kiso = niso ? (niso + 1) / (smax - smin) : 0;
  /* depth jump beyond which neighbouring samples are on different sheets (no isoline between them) */
  double ztol = 0.015 * (diag > 0 ? diag : 1);
  const double L[3] = {0.3 / 1.1180339887, 0.4 / 1.1180339887, 1.0 / 1.1180339887}; /* |(0.3,0.4,1)| */
  double h[3] = {L[0], L[1], L[2] + 1}, hn = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  for (int d = 0; d < 3; d++) h[d] /= hn;
  int ow = o->width, failed = 0;

#pragma omp parallel
  {
    size_t cap = (size_t)W * (BS + 2);
    gbuf g = {W, H, 0, malloc(sizeof(float) * cap), malloc(sizeof(int) * cap), malloc(sizeof(float) * cap),
              malloc(sizeof(float) * cap)};
    float *sval = niso ? malloc(sizeof(float) * cap) : NULL;
    int ok = g.z && g.id && g.b1 && g.b2 && (!niso || sval);
    if (!ok) {
#pragma omp atomic write
      failed = 1;
    }
#pragma omp for schedule(dynamic, 1)
    for (int b = 0; b < nb; b++) {
      if (!ok) continue;
      int gy0 = b * BS - 1, gy1 = (b + 1) * BS; /* inclusive sample rows, apron included */
      if (gy0 < 0) gy0 = 0;
      if (gy1 > H - 1) gy1 = H - 1;
      g.y0 = gy0;
      size_t nrow = (size_t)(gy1 - gy0 + 1) * W;
      for (size_t i = 0; i < nrow; i++) g.z[i] = -INFINITY, g.id[i] = -1;
      for (int q = bstart[b]; q < bstart[b + 1]; q++) {
        int f = blist[q];
        const int *t = m->F + 3 * (size_t)f;
        raster_triangle(&g, f, P + 3 * (size_t)t[0], P + 3 * (size_t)t[1], P + 3 * (size_t)t[2], gy0, gy1);
      }
      for (int k = 0; k < sc->nmarkers; k++) raster_sphere(&g, k, MP + 3 * (size_t)k, mrad * scale, mrad, gy0, gy1);
      if (niso)
        for (size_t i = 0; i < nrow; i++) {
          int f = g.id[i];
          if (f < 0) {
            sval[i] = NAN;
            continue;
          }
          const int *t = m->F + 3 * (size_t)f;
          double w1 = g.b1[i], w2 = g.b2[i];
          double v = (1 - w1 - w2) * sc->scalar[t[0]] + w1 * sc->scalar[t[1]] + w2 * sc->scalar[t[2]];
          sval[i] = (float)floor((v - smin) * kiso);
        }
      int yend = (b + 1) * BAND_ROWS < o->height ? (b + 1) * BAND_ROWS : o->height;
      for (int y = b * BAND_ROWS; y < yend; y++)
        for (int x = 0; x < ow; x++) {
          double acc[3] = {0, 0, 0};
          for (int j = 0; j < s; j++)
            for (int i = 0; i < s; i++) {
              int sx = x * s + i, sy = y * s + j;
              size_t idx = (size_t)(sy - gy0) * W + sx;
              int id = g.id[idx];
              if (id == -1) {
                for (int c = 0; c < 3; c++) acc[c] += o->background[c];
                continue;
              }
              double n[3], base[3];
              if (id >= 0) {
                const int *t = m->F + 3 * (size_t)id;
                double w1 = g.b1[idx], w2 = g.b2[idx], w0 = 1 - w1 - w2;
                for (int d = 0; d < 3; d++)
                  n[d] = w0 * N[3 * (size_t)t[0] + d] + w1 * N[3 * (size_t)t[1] + d] + w2 * N[3 * (size_t)t[2] + d];
                for (int c = 0; c < 3; c++) {
                  if (sc->face_rgb) base[c] = sc->face_rgb[3 * (size_t)id + c];
                  else if (sc->vertex_rgb)
                    base[c] = w0 * sc->vertex_rgb[3 * (size_t)t[0] + c] + w1 * sc->vertex_rgb[3 * (size_t)t[1] + c] +
                              w2 * sc->vertex_rgb[3 * (size_t)t[2] + c];
                  else base[c] = 200;
                }
              } else {
                int k = -(id + 2);
                double nx = g.b1[idx], ny = g.b2[idx], nz = 1 - nx * nx - ny * ny;
                n[0] = nx, n[1] = ny, n[2] = nz > 0 ? sqrt(nz) : 0;
                for (int c = 0; c < 3; c++) base[c] = sc->marker_rgb ? sc->marker_rgb[3 * (size_t)k + c] : 20;
              }
              double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
              double diff = 1, spec = 0;
              if (nl > 0) {
                if (n[2] < 0) nl = -nl; /* two-sided: light the side facing the camera */
                diff = fabs(n[0] * L[0] + n[1] * L[1] + n[2] * L[2]) / fabs(nl);
                double ndh = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / nl;
                if (ndh > 0) { /* 0.25·ndh^40 by squaring */
                  double p2 = ndh * ndh, p4 = p2 * p2, p8 = p4 * p4, p16 = p8 * p8, p32 = p16 * p16;
                  spec = 0.25 * p32 * p8;
                }
              }
              double shade = 0.35 + 0.65 * diff;
              int iso = 0;
              if (niso && id >= 0 && !isnan(sval[idx])) {
                static const int DX[4] = {1, -1, 0, 0}, DY[4] = {0, 0, 1, -1};
                for (int q = 0; q < 4 && !iso; q++) {
                  int nx = sx + DX[q], ny = sy + DY[q];
                  if (nx < 0 || nx >= W || ny < gy0 || ny > gy1) continue;
                  size_t nidx = (size_t)(ny - gy0) * W + nx;
                  if (g.id[nidx] < 0 || isnan(sval[nidx]) || fabs(g.z[nidx] - g.z[idx]) > ztol) continue;
                  /* one sample on each side of a level: a line of constant width (one pixel at s = 2) */
                  if (sval[nidx] != sval[idx]) iso = 1;
                }
              }
              for (int c = 0; c < 3; c++) {
                double v = iso ? sc->isoline_rgb[c] : base[c] * shade + 255 * spec;
                acc[c] += lum_clamp(v);
              }
            }
          for (int c = 0; c < 3; c++) rgb[3 * ((size_t)y * ow + x) + c] = (unsigned char)(acc[c] / (s * s) + 0.5);
        }
    }
    free(g.z); free(g.id); free(g.b1); free(g.b2); free(sval);
  }
  free(P); free(N); free(MP); free(bstart); free(blist);
  if (failed) return ss_fail(err, SS_ERR_NOMEM, "out of memory for a %dx%d render", W, H);
  return SS_OK;
}

ss_status ss_render_mesh(const ss_mesh *m, const unsigned char *vertex_rgb, const unsigned char *face_rgb,
                         const ss_render_options *o, unsigned char *rgb, ss_error *err) {
  ss_render_scene sc;
  ss_render_scene_init(&sc, m);
  sc.vertex_rgb = vertex_rgb;
  sc.face_rgb = face_rgb;
  return ss_render(&sc, o, rgb, err);
}
