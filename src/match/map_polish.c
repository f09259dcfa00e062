/* ss_map_polish: a point map X -> Y made to fit the surfaces, by a non-rigid ICP whose deformation of
 * X is as rigid as possible (ARAP, Sorkine & Alexa 2007) and whose correspondences are the nearest
 * points of Y facing the same way. A spectral refinement (ZoomOut) leaves a map off by about an edge
 * length nearly everywhere when the poses stretch the surface; this step is a spatial objective that
 * does not share that bias (docs/tuning.md, "The map kept, polished on the surfaces"). */
#include "mesh/knn3.h"
#include "mesh/mesh_geometry.h"
#include "linalg/cholmod_wrap.h"
#include "specseg/geodesic.h"
#include "specseg/laplacian.h"
#include "specseg/match.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ss_map_polish_default_options(ss_map_polish_options *o) {
  memset(o, 0, sizeof *o);
  o->rounds = 30;
  o->steps = 3;
  o->w_surface_first = 0.1, o->w_surface_last = 1;
  o->w_map_first = 0.3, o->w_map_last = 0.001;
  o->neighbours = 16;
  o->min_normal_dot = 0;
  o->max_move = 0.1;
  o->mend_mirrored = 1;
}

/* a given image farther from its neighbours' images than this many times the edges between them
 * (the median over the neighbours) is an outlier of the given map: it does not pull */
#define TEAR_RATIO 5.0

static int options_ok(const ss_map_polish_options *o) {
  const double w[4] = {o->w_surface_first, o->w_surface_last, o->w_map_first, o->w_map_last};
  for (int i = 0; i < 4; i++)
    if (!(w[i] > 0 && w[i] <= 1e6)) return 0;
  return o->rounds >= 0 && o->rounds <= 10000 && o->steps >= 1 && o->steps <= 100 && o->neighbours >= 1 &&
         o->neighbours <= 64 && o->min_normal_dot >= -1 && o->min_normal_dot < 1 && o->max_move > 0 &&
         o->max_move <= 1e6 && (o->mend_mirrored == 0 || o->mend_mirrored == 1);
}

/* the area-weighted vertex normals of positions P over the faces F (zero where no face or all
 * degenerate) */
static void vertex_normals(int nv, int nf, const int *F, const double *P, double *N) {
  memset(N, 0, sizeof(double) * 3 * (size_t)nv);
  for (int f = 0; f < nf; f++) {
    const double *a = P + 3 * (size_t)F[3 * f], *b = P + 3 * (size_t)F[3 * f + 1], *c = P + 3 * (size_t)F[3 * f + 2];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < 3; d++) N[3 * (size_t)F[3 * f + k] + d] += n[d];
  }
  for (int i = 0; i < nv; i++) {
    double *n = N + 3 * (size_t)i;
    const double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0) n[0] /= l, n[1] /= l, n[2] /= l;
  }
}

/* The rotation R (row-major, kept as the unit quaternion q: w, x, y, z) maximising tr(Rᵀ A), warm
 * started from q: rotate by ω = Σ_c r_c × a_c / |Σ_c r_c · a_c| until ω vanishes (Müller, Bender,
 * Chentanez & Macklin 2016, "A robust method to extract the rotational part of deformations").
 * Unlike the SVD it needs no care where A is rank-deficient, as on a flat vertex star. */
static void quat_to_rot(const double q[4], double R[9]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  R[0] = 1 - 2 * (y * y + z * z), R[1] = 2 * (x * y - w * z), R[2] = 2 * (x * z + w * y);
  R[3] = 2 * (x * y + w * z), R[4] = 1 - 2 * (x * x + z * z), R[5] = 2 * (y * z - w * x);
  R[6] = 2 * (x * z - w * y), R[7] = 2 * (y * z + w * x), R[8] = 1 - 2 * (x * x + y * y);
}

static void fit_rotation(const double A[9], double q[4], double R[9]) {
  for (int it = 0; it < 20; it++) {
    quat_to_rot(q, R);
    double om[3] = {0, 0, 0}, dot = 0;
    for (int c = 0; c < 3; c++) {
      const double r[3] = {R[c], R[3 + c], R[6 + c]}, a[3] = {A[c], A[3 + c], A[6 + c]};
      om[0] += r[1] * a[2] - r[2] * a[1], om[1] += r[2] * a[0] - r[0] * a[2], om[2] += r[0] * a[1] - r[1] * a[0];
      dot += r[0] * a[0] + r[1] * a[1] + r[2] * a[2];
    }
    const double s = 1 / (fabs(dot) + 1e-300);
    om[0] *= s, om[1] *= s, om[2] *= s;
    const double ang = sqrt(om[0] * om[0] + om[1] * om[1] + om[2] * om[2]);
    if (!(ang > 1e-5)) return; /* (a rotation closer than that moves no vertex of a unit-area shape) */
    const double h = 0.5 * ang, sh = sin(h) / ang;
    const double p[4] = {cos(h), om[0] * sh, om[1] * sh, om[2] * sh};
    const double n[4] = {p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
                         p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
                         p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
                         p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0]};
    const double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] + n[3] * n[3]);
    for (int k = 0; k < 4; k++) q[k] = n[k] / l;
  }
  quat_to_rot(q, R);
}

/* Whether t lies within `radius` of s along Y's edges: a Dijkstra from s, stopped when t is reached
 * or everything within the radius is settled (dist: all INFINITY between calls; heap and key:
 * room for one entry per arc; touched: one per vertex). A polished image must stay that near the
 * given one: where two parts of Y touch, the nearest vertex facing the right way can lie on the other
 * part, geodesically far (TOSCA_r cats' paws against their bodies). */
typedef struct reach_ws {
  double *dist, *key;
  int *heap, *touched;
} reach_ws;

static int within(const ss_graph *g, int s, int t, double radius, reach_ws *w) {
  if (s == t) return 1;
  int hn = 0, nt = 0, found = 0;
  w->dist[s] = 0, w->touched[nt++] = s, w->heap[hn] = s, w->key[hn++] = 0;
  while (hn > 0 && !found) {
    const int u = w->heap[0];
    const double du = w->key[0];
    hn--; /* pop: the last entry sifted down from the root */
    if (hn > 0) {
      const int hv = w->heap[hn];
      const double hk = w->key[hn];
      int c = 0;
      for (;;) {
        int l = 2 * c + 1;
        if (l >= hn) break;
        if (l + 1 < hn && w->key[l + 1] < w->key[l]) l++;
        if (w->key[l] >= hk) break;
        w->heap[c] = w->heap[l], w->key[c] = w->key[l], c = l;
      }
      w->heap[c] = hv, w->key[c] = hk;
    }
    if (du > w->dist[u]) continue; /* a stale entry (lazy deletion) */
    if (u == t) found = 1;
    for (int p = g->ptr[u]; p < g->ptr[u + 1] && !found; p++) {
      const int v = g->adj[p];
      const double nd = du + g->w[p];
      if (nd >= w->dist[v] || nd > radius) continue;
      if (w->dist[v] == INFINITY) w->touched[nt++] = v;
      w->dist[v] = nd;
      int c = hn++; /* push, sifted up */
      while (c > 0 && w->key[(c - 1) / 2] > nd)
        w->heap[c] = w->heap[(c - 1) / 2], w->key[c] = w->key[(c - 1) / 2], c = (c - 1) / 2;
      w->heap[c] = v, w->key[c] = nd;
    }
  }
  for (int k = 0; k < nt; k++) w->dist[w->touched[k]] = INFINITY;
  return found;
}

/* per vertex i of X at positions P: the nearest of Y's vertices (within `neighbours`) whose normal
 * faces the same way as P's (dot > min_dot), else fallback[i] */
static void facing_nearest(const ssi_knn3 *tree, int nv, const double *P, const double *NP, const double *NY,
                           const int *fallback, int kq, double min_dot, int *out) {
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nv; i++) {
    int idx[64];
    double d2[64];
    const double *n = NP + 3 * (size_t)i;
    /* the nearest alone first: it faces the same way almost everywhere, and the k nearest start with it */
    ssi_knn3_query(tree, P + 3 * (size_t)i, 1, idx, d2);
    const double *m0 = NY + 3 * (size_t)idx[0];
    if (n[0] * m0[0] + n[1] * m0[1] + n[2] * m0[2] > min_dot) {
      out[i] = idx[0];
      continue;
    }
    ssi_knn3_query(tree, P + 3 * (size_t)i, kq, idx, d2);
    int got = fallback[i];
    for (int c = 1; c < kq; c++) {
      const double *m = NY + 3 * (size_t)idx[c];
      if (n[0] * m[0] + n[1] * m[1] + n[2] * m[2] > min_dot) {
        got = idx[c];
        break;
      }
    }
    out[i] = got;
  }
}

/* what one polish pass works with: both shapes at unit area, X's clamped cotangent Laplacian L and
 * vertex areas a, Y's normals, kd-tree and edge graph, the factor, and the pass's work arrays */
typedef struct polish_ctx {
  ss_map_polish_options o;
  const ss_mesh *X;
  int nx, ny, kq;
  double *Xn, *Yn, *NY, *P, *NP, *tgt, *B, *sol, *a, *d, *R, *q;
  int *near, *pulls, *guard;
  ss_sparse L;
  ssi_knn3 *tree;
  ssi_chol *chol;
  ss_graph gy;
  reach_ws rw;
} polish_ctx;

/* A region of X whose images are turned over is mended in a second pass when it is at least this
 * share of X's vertices and thick: a torso's front sent to its back, out of max_move's reach. A thin
 * part turned over (a leg's front and back exchanged) the first pass mends, and released it drifts
 * onto the parts beside it (docs/tuning.md, "Mirrored regions"). */
#define MIRROR_FACING (-0.3) /* X's normals on the images against Y's there, smoothed: below this */
#define MIRROR_SMOOTHING 2   /* rounds of 1-ring averaging of that facing */
#define MIRROR_MIN_SHARE 0.005
#define MIRROR_THICKNESS 0.08 /* no vertex of Y facing the other way this near (unit area), at half of them */
#define MIRROR_MARGIN 4       /* rings of X released around such a region and around the map's tears */
#define MIRROR_FILL_SWEEPS 300 /* Gauss-Seidel sweeps placing the released vertices between the rest */

/* How X's faces laid on their images (normals NP) face against Y's there (NY at T's images): each
 * vertex's normals' dot product into f (NULL: not kept), and their area-weighted sum (weights a),
 * negative when most of X faces the other way */
static double facing_vote(int nx, const double *a, const double *NP, const double *NY, const int *T, double *f) {
  double agree = 0;
  for (int i = 0; i < nx; i++) {
    const double *n = NP + 3 * (size_t)i, *m = NY + 3 * (size_t)T[i];
    const double dot = n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
    if (f) f[i] = dot;
    agree += a[i] * dot;
  }
  return agree;
}

/* One pass: polish the map T into out (out may be T). released (NULL: none): vertices of X that, with
 * T's tears and MIRROR_MARGIN rings around both, do not pull towards their images, start between the
 * others (harmonic) and may move anywhere but near a neighbour that pulls. */
static ss_status polish_pass(polish_ctx *c, const int *T, const int *released, int *out, ss_error *err) {
  const ss_map_polish_options *o = &c->o;
  const ss_sparse *L = &c->L;
  const int nx = c->nx;
  const double *Xn = c->Xn, *Yn = c->Yn, *a = c->a;
  double *P = c->P, *NP = c->NP, *NY = c->NY, *tgt = c->tgt, *B = c->B, *sol = c->sol, *d = c->d, *R = c->R,
         *q = c->q;
  int *pulls = c->pulls, *guard = c->guard;
  ss_status st;
  /* the given images that tear the surface (an image far from its neighbours' images, relative to
   * the edges between them: a given map's outliers) do not pull: such a vertex follows its neighbours,
   * starts at their images' mean, and its image may move within max_move of a neighbour's given image
   * instead of its own */
  for (int i = 0; i < nx; i++) {
    double r[64];
    int m = 0;
    for (int p = L->colptr[i]; p < L->colptr[i + 1] && m < 64; p++) {
      const int j = L->rowind[p];
      if (j == i) continue;
      const double *xi = Xn + 3 * (size_t)i, *xj = Xn + 3 * (size_t)j;
      const double *yi = Yn + 3 * (size_t)T[i], *yj = Yn + 3 * (size_t)T[j];
      const double ex = sqrt((xi[0] - xj[0]) * (xi[0] - xj[0]) + (xi[1] - xj[1]) * (xi[1] - xj[1]) +
                             (xi[2] - xj[2]) * (xi[2] - xj[2]));
      const double ey = sqrt((yi[0] - yj[0]) * (yi[0] - yj[0]) + (yi[1] - yj[1]) * (yi[1] - yj[1]) +
                             (yi[2] - yj[2]) * (yi[2] - yj[2]));
      double v = ex > 0 ? ey / ex : (ey > 0 ? INFINITY : 0);
      int k = m++; /* insertion, sorted */
      while (k > 0 && r[k - 1] > v) r[k] = r[k - 1], k--;
      r[k] = v;
    }
    pulls[i] = (m == 0 || r[(m - 1) / 2] <= TEAR_RATIO) && !(released && released[i]);
  }
  if (released) /* the regions and the given map's tears (their seams), grown by MIRROR_MARGIN rings */
    for (int r = 0; r < MIRROR_MARGIN; r++) {
      for (int i = 0; i < nx; i++) c->near[i] = !pulls[i];
      for (int i = 0; i < nx; i++)
        if (c->near[i])
          for (int p = L->colptr[i]; p < L->colptr[i + 1]; p++) pulls[L->rowind[p]] = 0;
    }
  for (int i = 0; i < nx; i++) {
    guard[i] = T[i];
    if (pulls[i]) continue;
    guard[i] = -1;
    for (int p = L->colptr[i]; p < L->colptr[i + 1]; p++)
      if (L->rowind[p] != i && pulls[L->rowind[p]]) {
        guard[i] = T[L->rowind[p]];
        break;
      }
  }
  for (int i = 0; i < nx; i++) {
    memcpy(P + 3 * (size_t)i, Yn + 3 * (size_t)T[i], sizeof(double) * 3);
    if (!pulls[i]) {
      double m[3] = {0, 0, 0};
      int k = 0;
      for (int p = L->colptr[i]; p < L->colptr[i + 1]; p++) {
        const int j = L->rowind[p];
        if (j == i || !pulls[j]) continue;
        for (int u = 0; u < 3; u++) m[u] += Yn[3 * (size_t)T[j] + u];
        k++;
      }
      if (k > 0)
        for (int u = 0; u < 3; u++) P[3 * (size_t)i + u] = m[u] / k;
    }
    q[4 * (size_t)i] = 1, q[4 * (size_t)i + 1] = q[4 * (size_t)i + 2] = q[4 * (size_t)i + 3] = 0;
  }
  if (released) /* the released region starts as the harmonic fill between the others' images */
    for (int s = 0; s < MIRROR_FILL_SWEEPS; s++)
      for (int i = 0; i < nx; i++) {
        if (pulls[i]) continue;
        double m[3] = {0, 0, 0};
        int k = 0;
        for (int p = L->colptr[i]; p < L->colptr[i + 1]; p++) {
          const int j = L->rowind[p];
          if (j == i) continue;
          for (int u = 0; u < 3; u++) m[u] += P[3 * (size_t)j + u];
          k++;
        }
        if (k > 0)
          for (int u = 0; u < 3; u++) P[3 * (size_t)i + u] = m[u] / k;
      }
  for (int r = 0; r < o->rounds; r++) {
    /* the weights move geometrically from their first to their last value: a stiff, map-led start,
     * then the surface takes over */
    const double t = o->rounds > 1 ? (double)r / (o->rounds - 1) : 1;
    const double ws = o->w_surface_first * pow(o->w_surface_last / o->w_surface_first, t);
    const double wm = o->w_map_first * pow(o->w_map_last / o->w_map_first, t);
    /* each vertex's target: its position projected onto the tangent plane of the facing nearest
     * vertex of Y (point-to-plane ICP) */
    vertex_normals(nx, c->X->nf, c->X->F, P, NP);
    if (r == 0) {
      /* X's faces laid on their images face as Y's there, mostly, when the two meshes are oriented
       * alike: otherwise (one faces inwards) Y's normals are turned round */
      if (facing_vote(nx, a, NP, NY, T, NULL) < 0)
        for (size_t i = 0; i < 3 * (size_t)c->ny; i++) NY[i] = -NY[i];
    }
    facing_nearest(c->tree, nx, P, NP, NY, T, c->kq, o->min_normal_dot, c->near);
    for (int i = 0; i < nx; i++) {
      const double *p = P + 3 * (size_t)i, *y = Yn + 3 * (size_t)c->near[i], *n = NY + 3 * (size_t)c->near[i];
      const double h = (p[0] - y[0]) * n[0] + (p[1] - y[1]) * n[1] + (p[2] - y[2]) * n[2];
      for (int u = 0; u < 3; u++) tgt[3 * (size_t)i + u] = p[u] - h * n[u];
      d[i] = a[i] * (ws + (pulls[i] ? wm : 0));
    }
    /* (one analysis: the diagonal alone changes from round to round) */
    if ((st = c->chol ? ssi_chol_refactor(c->chol, L, 1, d, err) : ssi_chol_factor(L, 1, d, &c->chol, err))) return st;
    for (int s = 0; s < o->steps; s++) {
      /* local: each vertex's rotation from its star's edges, rest (X) to current (P) */
#pragma omp parallel for schedule(static)
      for (int i = 0; i < nx; i++) {
        double A[9] = {0};
        for (int p = L->colptr[i]; p < L->colptr[i + 1]; p++) {
          const int j = L->rowind[p];
          if (j == i) continue;
          const double w = -L->val[p];
          const double e[3] = {Xn[3 * (size_t)i] - Xn[3 * (size_t)j], Xn[3 * (size_t)i + 1] - Xn[3 * (size_t)j + 1],
                               Xn[3 * (size_t)i + 2] - Xn[3 * (size_t)j + 2]};
          const double f[3] = {P[3 * (size_t)i] - P[3 * (size_t)j], P[3 * (size_t)i + 1] - P[3 * (size_t)j + 1],
                               P[3 * (size_t)i + 2] - P[3 * (size_t)j + 2]};
          for (int u = 0; u < 3; u++)
            for (int v = 0; v < 3; v++) A[3 * u + v] += w * f[u] * e[v];
        }
        fit_rotation(A, q + 4 * (size_t)i, R + 9 * (size_t)i);
      }
      /* global: (L + diag(d)) P = Σ_j w_ij (R_i + R_j)/2 (x_i - x_j) + a_i (ws target_i + wm Y[T(i)]) */
#pragma omp parallel for schedule(static)
      for (int i = 0; i < nx; i++) {
        double b[3] = {0, 0, 0};
        const double *Ri = R + 9 * (size_t)i;
        for (int p = L->colptr[i]; p < L->colptr[i + 1]; p++) {
          const int j = L->rowind[p];
          if (j == i) continue;
          const double w = -0.5 * L->val[p], *Rj = R + 9 * (size_t)j;
          const double e[3] = {Xn[3 * (size_t)i] - Xn[3 * (size_t)j], Xn[3 * (size_t)i + 1] - Xn[3 * (size_t)j + 1],
                               Xn[3 * (size_t)i + 2] - Xn[3 * (size_t)j + 2]};
          for (int u = 0; u < 3; u++)
            b[u] += w * ((Ri[3 * u] + Rj[3 * u]) * e[0] + (Ri[3 * u + 1] + Rj[3 * u + 1]) * e[1] +
                         (Ri[3 * u + 2] + Rj[3 * u + 2]) * e[2]);
        }
        const double *yt = Yn + 3 * (size_t)T[i];
        const double wi = pulls[i] ? wm : 0;
        for (int u = 0; u < 3; u++) B[(size_t)u * nx + i] = b[u] + a[i] * (ws * tgt[3 * (size_t)i + u] + wi * yt[u]);
      }
      if ((st = ssi_chol_solve(c->chol, B, sol, 3, err))) return st;
      for (int i = 0; i < nx; i++)
        for (int u = 0; u < 3; u++) P[3 * (size_t)i + u] = sol[(size_t)u * nx + i];
    }
  }
  /* the map: each vertex's facing nearest vertex of Y at its polished position */
  vertex_normals(nx, c->X->nf, c->X->F, P, NP);
  for (int i = 0; i < nx; i++) {
    int idx[64];
    double d2[64];
    const double *n = NP + 3 * (size_t)i;
    ssi_knn3_query(c->tree, P + 3 * (size_t)i, c->kq, idx, d2);
    int got = T[i];
    for (int k = 0; k < c->kq; k++) {
      const double *m = NY + 3 * (size_t)idx[k];
      if (n[0] * m[0] + n[1] * m[1] + n[2] * m[2] > o->min_normal_dot &&
          (guard[i] < 0 || within(&c->gy, guard[i], idx[k], o->max_move, &c->rw))) {
        got = idx[k];
        break;
      }
    }
    out[i] = got;
  }
  return SS_OK;
}

/* Whether Y has a vertex facing against normal n within `radius` of y (nearest first, the search
 * widened until it passes the radius) */
static int facing_back_within(const polish_ctx *c, const double *y, const double *n, double radius, int *idx,
                              double *d2) {
  for (int k = 64;; k *= 4) {
    if (k > c->ny) k = c->ny;
    ssi_knn3_query(c->tree, y, k, idx, d2);
    for (int j = 0; j < k && d2[j] <= radius * radius; j++) {
      const double *m = c->NY + 3 * (size_t)idx[j];
      if (n[0] * m[0] + n[1] * m[1] + n[2] * m[2] < -0.5) return 1;
    }
    if (d2[k - 1] > radius * radius || k == c->ny) return 0;
  }
}

/* The vertices of X in thick regions that the map T turns over (see MIRROR_*) into released (0/1);
 * *found: whether there is any. */
static ss_status mirrored_regions(polish_ctx *c, const int *T, int *released, int *found, ss_error *err) {
  const int nx = c->nx;
  const ss_sparse *L = &c->L;
  double *f = malloc(sizeof(double) * (size_t)nx), *g = malloc(sizeof(double) * (size_t)nx),
         *d2 = malloc(sizeof(double) * (size_t)c->ny);
  int *stack = malloc(sizeof(int) * (size_t)nx), *seen = calloc((size_t)nx, sizeof(int)),
      *idx = malloc(sizeof(int) * (size_t)c->ny);
  *found = 0;
  if (!f || !g || !d2 || !stack || !seen || !idx) {
    free(f), free(g), free(d2), free(stack), free(seen), free(idx);
    return ss_fail(err, SS_ERR_NOMEM, "map polish: out of memory");
  }
  /* f: X's normals laid on the images against Y's there (Y's as the first pass turned them) */
  for (int i = 0; i < nx; i++) memcpy(c->P + 3 * (size_t)i, c->Yn + 3 * (size_t)T[i], sizeof(double) * 3);
  vertex_normals(nx, c->X->nf, c->X->F, c->P, c->NP);
  /* (most of the map keeps the orientation: the rest is what is turned over) */
  if (facing_vote(nx, c->a, c->NP, c->NY, T, f) < 0)
    for (int i = 0; i < nx; i++) f[i] = -f[i];
  for (int s = 0; s < MIRROR_SMOOTHING; s++) {
    for (int i = 0; i < nx; i++) {
      double sum = 0, w = 0;
      for (int p = L->colptr[i]; p < L->colptr[i + 1]; p++) {
        const int j = L->rowind[p];
        sum += c->a[j] * f[j], w += c->a[j];
      }
      g[i] = w > 0 ? sum / w : f[i];
    }
    memcpy(f, g, sizeof(double) * (size_t)nx);
  }
  /* the connected regions below MIRROR_FACING (seen: visited) */
  for (int i = 0; i < nx; i++) released[i] = 0;
  for (int i = 0; i < nx; i++) {
    if (seen[i] || !(f[i] < MIRROR_FACING)) continue;
    int top = 0, n = 0;
    stack[top++] = i, seen[i] = 1;
    while (top > n) { /* stack[0..n) visited, [n, top) to visit: it ends holding the region */
      const int v = stack[n++];
      for (int p = L->colptr[v]; p < L->colptr[v + 1]; p++) {
        const int j = L->rowind[p];
        if (!seen[j] && f[j] < MIRROR_FACING) seen[j] = 1, stack[top++] = j;
      }
    }
    if (n < MIRROR_MIN_SHARE * nx) continue;
    int thick = 0;
    for (int k = 0; k < n; k++) {
      const int v = stack[k];
      thick += !facing_back_within(c, c->Yn + 3 * (size_t)T[v], c->NY + 3 * (size_t)T[v], MIRROR_THICKNESS, idx, d2);
    }
    if (2 * thick < n) continue;
    for (int k = 0; k < n; k++) released[stack[k]] = 1;
    *found = 1;
  }
  free(f), free(g), free(d2), free(stack), free(seen), free(idx);
  return SS_OK;
}

ss_status ss_map_polish(const ss_mesh *X, const ss_mesh *Y, const int *map_in, const ss_map_polish_options *opts,
                        int *map_out, ss_error *err) {
  ss_map_polish_options o;
  ss_status st0;
  if (opts) o = *opts;
  else ss_map_polish_default_options(&o);
  if (!X || !Y || !X->V || !Y->V || !X->F || !Y->F || X->nv < 1 || Y->nv < 1 || X->nf < 1 || Y->nf < 1)
    return ss_fail(err, SS_ERR_INVALID, "map polish: empty or NULL mesh");
  if (!map_in || !map_out) return ss_fail(err, SS_ERR_INVALID, "map polish: NULL map");
  if (!options_ok(&o))
    return ss_fail(err, SS_ERR_INVALID, "map polish: rounds 0..10000, steps 1..100, the four weights in (0, 1e6], "
                   "neighbours 1..64, min_normal_dot in [-1, 1), max_move in (0, 1e6], mend_mirrored 0 or 1");
  const int nx = X->nv, ny = Y->nv;
  for (int i = 0; i < nx; i++)
    if (map_in[i] < 0 || map_in[i] >= ny)
      return ss_fail(err, SS_ERR_INVALID, "map polish: map entry %d (%d) is not a vertex of Y (0..%d)", i, map_in[i],
                     ny - 1);
  for (int f = 0; f < 3 * X->nf; f++)
    if (X->F[f] < 0 || X->F[f] >= nx) return ss_fail(err, SS_ERR_INVALID, "map polish: a face of X is off its vertices");
  for (int f = 0; f < 3 * Y->nf; f++)
    if (Y->F[f] < 0 || Y->F[f] >= ny) return ss_fail(err, SS_ERR_INVALID, "map polish: a face of Y is off its vertices");
  if ((st0 = ssi_mesh_check_coordinates(X, "map polish: X", err)) ||
      (st0 = ssi_mesh_check_coordinates(Y, "map polish: Y", err)))
    return st0;
  const double ax = ss_mesh_area(X), ay = ss_mesh_area(Y);
  if (!(ax > 0 && ay > 0 && isfinite(ax) && isfinite(ay)))
    return ss_fail(err, SS_ERR_INVALID, "map polish: a mesh of zero or non-finite area");
  if (o.rounds == 0) {
    memmove(map_out, map_in, sizeof(int) * (size_t)nx);
    return SS_OK;
  }
  const double sx = 1 / sqrt(ax), sy = 1 / sqrt(ay); /* both at unit area: the step does not see scale */

  ss_status st = SS_OK;
  polish_ctx c = {0};
  c.o = o, c.X = X, c.nx = nx, c.ny = ny;
  c.kq = o.neighbours < ny ? o.neighbours : ny;
  const size_t n3 = 3 * (size_t)nx;
  ss_sparse W = {0};
  int *T = malloc(sizeof(int) * (size_t)nx), *released = NULL;
  c.Xn = malloc(sizeof(double) * n3), c.Yn = malloc(sizeof(double) * 3 * (size_t)ny);
  c.NY = malloc(sizeof(double) * 3 * (size_t)ny), c.P = malloc(sizeof(double) * n3);
  c.NP = malloc(sizeof(double) * n3), c.tgt = malloc(sizeof(double) * n3), c.B = malloc(sizeof(double) * n3);
  c.sol = malloc(sizeof(double) * n3), c.a = malloc(sizeof(double) * (size_t)nx);
  c.d = malloc(sizeof(double) * (size_t)nx), c.R = malloc(sizeof(double) * 9 * (size_t)nx);
  c.q = malloc(sizeof(double) * 4 * (size_t)nx);
  c.near = malloc(sizeof(int) * (size_t)nx), c.pulls = malloc(sizeof(int) * (size_t)nx);
  c.guard = malloc(sizeof(int) * (size_t)nx);
  if (!T || !c.Xn || !c.Yn || !c.NY || !c.P || !c.NP || !c.tgt || !c.B || !c.sol || !c.a || !c.d || !c.R || !c.q ||
      !c.near || !c.pulls || !c.guard) {
    st = ss_fail(err, SS_ERR_NOMEM, "map polish: out of memory");
    goto done;
  }
  memcpy(T, map_in, sizeof(int) * (size_t)nx);
  for (size_t i = 0; i < n3; i++) c.Xn[i] = X->V[i] * sx;
  for (size_t i = 0; i < 3 * (size_t)ny; i++) c.Yn[i] = Y->V[i] * sy;
  /* ARAP's edge weights: the cotangent weights, clamped positive (a negative weight, across an obtuse
   * pair of angles, would reward stretching that edge) */
  ss_mesh Xu = *X;
  Xu.V = c.Xn;
  if ((st = ss_cotan_stiffness(&Xu, &W, err))) goto done;
  if ((st = ss_mass_lumped(&Xu, SS_MASS_BARYCENTRIC, c.a, err))) goto done;
  {
    double mean = 0;
    for (int i = 0; i < nx; i++) mean += c.a[i];
    mean /= nx;
    for (int i = 0; i < nx; i++) c.a[i] = c.a[i] / mean > 1e-6 ? c.a[i] / mean : 1e-6; /* (an unreferenced vertex) */
  }
  /* L: the weighted graph Laplacian of the clamped weights, same pattern as W */
  ss_sparse *L = &c.L;
  L->nrows = L->ncols = nx;
  L->colptr = malloc(sizeof(int) * ((size_t)nx + 1));
  L->rowind = malloc(sizeof(int) * (size_t)W.colptr[nx]);
  L->val = malloc(sizeof(double) * (size_t)W.colptr[nx]);
  if (!L->colptr || !L->rowind || !L->val) {
    st = ss_fail(err, SS_ERR_NOMEM, "map polish: out of memory");
    goto done;
  }
  memcpy(L->colptr, W.colptr, sizeof(int) * ((size_t)nx + 1));
  memcpy(L->rowind, W.rowind, sizeof(int) * (size_t)W.colptr[nx]);
  for (int j = 0; j < nx; j++) {
    double diag = 0;
    int dpos = -1;
    for (int p = W.colptr[j]; p < W.colptr[j + 1]; p++) {
      if (W.rowind[p] == j) {
        dpos = p;
        continue;
      }
      const double w = -W.val[p] > 1e-6 ? -W.val[p] : 1e-6;
      L->val[p] = -w, diag += w;
    }
    if (dpos >= 0) L->val[dpos] = diag;
    else if (diag != 0) { /* (ss_cotan_stiffness stores every diagonal of a referenced vertex) */
      st = ss_fail(err, SS_ERR_NUMERIC, "map polish: stiffness without a diagonal");
      goto done;
    }
  }
  vertex_normals(ny, Y->nf, Y->F, c.Yn, c.NY);
  if ((st = ssi_knn3_build(ny, c.Yn, &c.tree, err))) goto done;
  {
    ss_mesh Yu = *Y;
    Yu.V = c.Yn;
    if ((st = ss_graph_edges(&Yu, &c.gy, err))) goto done;
    const size_t arcs = (size_t)c.gy.ptr[ny] + 1;
    c.rw.dist = malloc(sizeof(double) * (size_t)ny), c.rw.touched = malloc(sizeof(int) * (size_t)ny);
    c.rw.heap = malloc(sizeof(int) * arcs), c.rw.key = malloc(sizeof(double) * arcs);
    if (!c.rw.dist || !c.rw.touched || !c.rw.heap || !c.rw.key) {
      st = ss_fail(err, SS_ERR_NOMEM, "map polish: out of memory");
      goto done;
    }
    for (int v = 0; v < ny; v++) c.rw.dist[v] = INFINITY;
  }
  if ((st = polish_pass(&c, T, NULL, map_out, err))) goto done;
  if (o.mend_mirrored) {
    /* a thick region the map turns over (a torso's front sent to its back) is out of the first pass's
     * reach: its images are held within max_move of the given ones. Released from them, it is placed
     * again by the deformation of the rest, from the first pass's map. */
    released = malloc(sizeof(int) * (size_t)nx);
    if (!released) {
      st = ss_fail(err, SS_ERR_NOMEM, "map polish: out of memory");
      goto done;
    }
    int found = 0;
    if ((st = mirrored_regions(&c, map_out, released, &found, err))) goto done;
    if (found) {
      memcpy(T, map_out, sizeof(int) * (size_t)nx);
      if ((st = polish_pass(&c, T, released, map_out, err))) goto done;
    }
  }
done:
  ss_sparse_free(&W), ss_sparse_free(&c.L);
  ssi_knn3_free(c.tree), ssi_chol_free(c.chol), ss_graph_free(&c.gy);
  free(c.rw.dist), free(c.rw.key), free(c.rw.heap), free(c.rw.touched);
  free(c.Xn), free(c.Yn), free(c.NY), free(c.P), free(c.NP), free(c.tgt), free(c.B), free(c.sol), free(c.a), free(c.d),
      free(c.R), free(c.q), free(c.near), free(c.pulls), free(c.guard), free(T), free(released);
  return st;
}
