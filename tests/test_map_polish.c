/* ss_map_polish and its kd-tree: the k nearest are those of a scan over every point (ties by index);
 * the identity of a shape onto itself, or onto a rotated, scaled and moved copy, stays the identity;
 * on the synthetic humanoid (poses share one vertex order: the truth is the identity) a map scrambled
 * within small neighbourhoods comes back much nearer the truth; the result does not depend on the
 * thread count; a mesh facing inwards leaves the map as given; bad input is refused. */
#include "mesh/knn3.h"
#include "specseg/fmap.h"
#include "specseg/match.h"
#include "specseg/synth.h"
#include "testlib.h"

#ifdef _OPENMP
#include <omp.h>
#endif

static double map_error(const ss_mesh *Y, int n, const int *map) {
  double mean = NAN;
  double *e = malloc(sizeof(double) * (size_t)n);
  ss_error err;
  if (!e || ss_map_geodesic_error(Y, n, map, NULL, NULL, e, &mean, &err)) mean = NAN;
  free(e);
  return mean;
}

/* the k nearest by a scan: sorted by squared distance, then index */
static void knn_scan(int n, const double *P, const double *q, int k, int *idx) {
  double *d = malloc(sizeof(double) * (size_t)n);
  int *o = malloc(sizeof(int) * (size_t)n);
  for (int i = 0; i < n; i++) {
    const double dx = P[3 * i] - q[0], dy = P[3 * i + 1] - q[1], dz = P[3 * i + 2] - q[2];
    d[i] = dx * dx + dy * dy + dz * dz, o[i] = i;
  }
  for (int a = 0; a < k; a++) { /* (selection: n is small) */
    int best = a;
    for (int b = a + 1; b < n; b++)
      if (d[o[b]] < d[o[best]] || (d[o[b]] == d[o[best]] && o[b] < o[best])) best = b;
    const int t = o[a];
    o[a] = o[best], o[best] = t;
    idx[a] = o[a];
  }
  free(d), free(o);
}

static unsigned rnd(unsigned *s) {
  *s = *s * 1103515245u + 12345u;
  return *s >> 8;
}

static void check_knn(void) {
  /* random points, then a grid (many equal distances), then points that all coincide */
  const int n = 700;
  double *P = malloc(sizeof(double) * 3 * n);
  unsigned s = 3;
  for (int set = 0; set < 3; set++) {
    for (int i = 0; i < n; i++)
      for (int c = 0; c < 3; c++)
        P[3 * i + c] = set == 0 ? (double)(rnd(&s) % 100000) / 1000 : set == 1 ? (double)((i / (c == 0 ? 1 : c == 1 ? 9 : 81)) % 9) : 1.5;
    ssi_knn3 *t = NULL;
    ss_error e;
    CHECK(ssi_knn3_build(n, P, &t, &e) == SS_OK);
    int bad = 0;
    for (int qi = 0; qi < 200 && t; qi++) {
      const double q[3] = {(double)(rnd(&s) % 11000) / 1000 - 0.5, (double)(rnd(&s) % 11000) / 1000 - 0.5,
                           qi % 7 == 0 ? P[3 * qi + 2] : (double)(rnd(&s) % 11000) / 1000 - 0.5};
      const int ks[4] = {1, 5, 16, 64};
      for (int a = 0; a < 4; a++) {
        int got[64], want[64];
        double d2[64];
        ssi_knn3_query(t, q, ks[a], got, d2);
        knn_scan(n, P, q, ks[a], want);
        bad += memcmp(got, want, sizeof(int) * (size_t)ks[a]) != 0;
      }
    }
    CHECK_MSG(bad == 0, "point set %d: %d queries differ from the scan", set, bad);
    ssi_knn3_free(t);
  }
  ssi_knn3 *t = NULL;
  ss_error e;
  CHECK(ssi_knn3_build(0, P, &t, &e) == SS_ERR_INVALID && !t);
  free(P);
}


/* an n x n grid of spacing h at (x0, y0, z), faces up (+z) */
static void grid(int n, double h, double x0, double y0, double z, double *V, int *F) {
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      double *p = V + 3 * (size_t)(j * n + i);
      p[0] = x0 + h * i, p[1] = y0 + h * j, p[2] = z;
    }
  int f = 0;
  for (int j = 0; j + 1 < n; j++)
    for (int i = 0; i + 1 < n; i++) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      F[3 * f] = a, F[3 * f + 1] = b, F[3 * f + 2] = d, f++;
      F[3 * f] = a, F[3 * f + 1] = d, F[3 * f + 2] = c, f++;
    }
}

/* Y two sheets facing the same way, B a hair above A and offset by half a cell, so that B's vertices
 * are the nearest to points of A between A's vertices; X a sheet offset the same way, mapped onto A.
 * B is not reachable from A along Y's edges, so no image leaves A. */
static void check_touching(void) {
  const int g = 12, nv = g * g, nf = 2 * (g - 1) * (g - 1);
  const double h = 1.0 / (g - 1);
  ss_mesh X = {0}, Y = {0};
  ss_error e;
  CHECK(ss_mesh_alloc(&X, nv, nf, &e) == SS_OK && ss_mesh_alloc(&Y, 2 * nv, 2 * nf, &e) == SS_OK);
  grid(g, h, 0.5 * h, 0.5 * h, 0, X.V, X.F);
  grid(g, h, 0, 0, 0, Y.V, Y.F);
  grid(g, h, 0.5 * h, 0.5 * h, 1e-4, Y.V + 3 * nv, Y.F + 3 * nf);
  for (int f = 0; f < 3 * nf; f++) Y.F[3 * nf + f] += nv;
  int *T = malloc(sizeof(int) * nv), *out = malloc(sizeof(int) * nv);
  for (int j = 0; j < g; j++)
    for (int i = 0; i < g; i++) T[j * g + i] = j * g + i; /* the A vertex half a cell below-left */
  CHECK(ss_map_polish(&X, &Y, T, NULL, out, &e) == SS_OK);
  int on_a = 0, near = 0;
  for (int v = 0; v < nv; v++) {
    on_a += out[v] < nv;
    const int di = abs(out[v] % g - T[v] % g), dj = abs(out[v] / g - T[v] / g);
    near += out[v] < nv && di <= 1 && dj <= 1;
  }
  CHECK_MSG(on_a == nv && near == nv, "%d of %d images on A, %d within a cell of the given", on_a, nv, near);
  free(T), free(out);
  ss_mesh_free(&X), ss_mesh_free(&Y);
}

/* A thick region turned over, which max_move keeps out of the first pass's reach: the humanoid's chest,
 * its front sent to the mirror image through the chest's middle (its back), the rest the truth
 * (poses 0 -> 2: the torso rigid, a leg raised). The second pass (mend_mirrored) places it again. */
static void check_mirrored(void) {
  ss_error e;
  ss_mesh X = {0}, Y = {0};
  CHECK(ss_synth_humanoid(0, &X, &e) == SS_OK && ss_synth_humanoid(2, &Y, &e) == SS_OK);
  const int n = X.nv;
  int *in = malloc(sizeof(int) * n), *out = malloc(sizeof(int) * n), *patch = calloc(n, sizeof(int));
  double cz = 0;
  int nb = 0, np = 0;
  for (int i = 0; i < n; i++) {
    const double *x = X.V + 3 * (size_t)i;
    if (x[1] > 1.2 && x[1] < 1.45 && fabs(x[0]) < 0.12) cz += x[2], nb++;
  }
  CHECK(nb > 0);
  cz /= nb;
  ssi_knn3 *tree = NULL;
  CHECK(ssi_knn3_build(n, Y.V, &tree, &e) == SS_OK);
  for (int i = 0; i < n && tree; i++) {
    const double *x = X.V + 3 * (size_t)i, *y = Y.V + 3 * (size_t)i;
    in[i] = i;
    if (!(x[1] > 1.2 && x[1] < 1.45 && fabs(x[0]) < 0.12 && x[2] > cz)) continue;
    const double m[3] = {y[0], y[1], 2 * cz - y[2]}; /* its mirror image; in[i]: Y's vertex nearest it */
    ssi_knn3_query(tree, m, 1, in + i, NULL);
    patch[i] = 1, np++;
  }
  ssi_knn3_free(tree);
  double *err = malloc(sizeof(double) * n), mean;
  ss_error ge;
  double on[3];
  const int *maps[3] = {in, out, out};
  for (int k = 0; k < 3; k++) {
    if (k > 0) {
      ss_map_polish_options o;
      ss_map_polish_default_options(&o);
      o.mend_mirrored = k == 2;
      CHECK(ss_map_polish(&X, &Y, in, &o, out, &e) == SS_OK);
    }
    CHECK(ss_map_geodesic_error(&Y, n, maps[k], NULL, NULL, err, &mean, &ge) == SS_OK);
    on[k] = 0;
    for (int i = 0; i < n; i++) on[k] += patch[i] ? err[i] / np : 0;
  }
  printf("humanoid 0 -> 2, the chest's front (%d vertices) sent to its back: error there %.4f, polished %.4f, "
         "with the second pass %.4f\n", np, on[0], on[1], on[2]);
  CHECK(np > 100);
  CHECK(on[1] > 0.5 * on[0]); /* out of the first pass's reach */
  CHECK(on[2] < 0.2 * on[0]);
  free(in), free(out), free(patch), free(err);
  ss_mesh_free(&X), ss_mesh_free(&Y);
}

int main(void) {
  check_knn();

  ss_error e;
  ss_mesh X = {0}, Y = {0}, Z = {0};
  CHECK(ss_synth_humanoid(0, &X, &e) == SS_OK);
  CHECK(ss_synth_humanoid(5, &Y, &e) == SS_OK);
  const int n = X.nv;
  CHECK(Y.nv == n);
  int *id = malloc(sizeof(int) * n), *rough = malloc(sizeof(int) * n), *out = malloc(sizeof(int) * n),
      *ref = malloc(sizeof(int) * n);
  for (int i = 0; i < n; i++) id[i] = i;

  /* fewer rounds where the property does not need them all (the test's time) */
  ss_map_polish_options o, few;
  ss_map_polish_default_options(&few);
  few.rounds = 6;

  /* the identity onto itself, and onto a copy rotated, scaled by 3.7 and moved: the identity */
  CHECK(ss_map_polish(&X, &X, id, &few, out, &e) == SS_OK);
  CHECK(memcmp(out, id, sizeof(int) * n) == 0);
  CHECK(ss_mesh_copy(&X, &Z, &e) == SS_OK);
  const double c = cos(0.7), s = sin(0.7);
  for (int i = 0; i < n; i++) {
    double *p = Z.V + 3 * (size_t)i;
    const double x = p[0], y = p[1];
    p[0] = 3.7 * (c * x - s * y) + 10, p[1] = 3.7 * (s * x + c * y) - 4, p[2] = 3.7 * p[2] + 0.5;
  }
  CHECK(ss_map_polish(&X, &Z, id, &few, out, &e) == SS_OK);
  CHECK(memcmp(out, id, sizeof(int) * n) == 0);

  /* pose 0 -> 5, the identity scrambled by 2-step walks: polished much nearer the truth */
  tl_scrambled_identity(X.nv, X.nf, X.F, 7u, rough);
  const double e_rough = map_error(&Y, n, rough);
  CHECK(ss_map_polish(&X, &Y, rough, NULL, out, &e) == SS_OK);
  const double e_polished = map_error(&Y, n, out);
  int exact = 0;
  for (int i = 0; i < n; i++) exact += out[i] == i;
  printf("humanoid pose 0 -> 5 (%d vertices), identity scrambled by 2-step walks: error %.4f, polished %.4f, %d of %d "
         "vertices exact\n", n, e_rough, e_polished, exact, n);
  CHECK(e_polished < 0.5 * e_rough);
  /* … and the truth itself stays near the truth */
  CHECK(ss_map_polish(&X, &Y, id, NULL, out, &e) == SS_OK);
  const double e_truth = map_error(&Y, n, out);
  printf("the truth polished: error %.4f\n", e_truth);
  CHECK(e_truth < 0.5 * e_rough);

  /* map_out may be map_in; one thread or two, the same map */
  CHECK(ss_map_polish(&X, &Y, rough, &few, ref, &e) == SS_OK);
  memcpy(out, rough, sizeof(int) * n);
  CHECK(ss_map_polish(&X, &Y, out, &few, out, &e) == SS_OK);
  CHECK(memcmp(out, ref, sizeof(int) * n) == 0);
#ifdef _OPENMP
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  CHECK(ss_map_polish(&X, &Y, rough, &few, out, &e) == SS_OK);
  CHECK(memcmp(out, ref, sizeof(int) * n) == 0);
  omp_set_num_threads(2);
  CHECK(ss_map_polish(&X, &Y, rough, &few, out, &e) == SS_OK);
  CHECK(memcmp(out, ref, sizeof(int) * n) == 0);
  omp_set_num_threads(threads);
#endif

  /* no rounds: the map as given */
  ss_map_polish_default_options(&o);
  o.rounds = 0;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_OK);
  CHECK(memcmp(out, rough, sizeof(int) * n) == 0);

  /* max_move: an image moves at most that far from the given one along Y's edges; next to nothing
   * keeps the map as given */
  ss_map_polish_default_options(&o);
  o.max_move = 1e-9;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_OK);
  CHECK(memcmp(out, rough, sizeof(int) * n) == 0);
  check_touching();
  check_mirrored();

  /* Y facing inwards (every face turned round): X's faces on their images face against Y's, so Y's
   * normals are turned round, and the map is the same */
  ss_mesh_free(&Z);
  CHECK(ss_mesh_copy(&Y, &Z, &e) == SS_OK);
  for (int f = 0; f < Z.nf; f++) {
    const int t = Z.F[3 * f + 1];
    Z.F[3 * f + 1] = Z.F[3 * f + 2], Z.F[3 * f + 2] = t;
  }
  CHECK(ss_map_polish(&X, &Z, rough, &few, out, &e) == SS_OK);
  CHECK(memcmp(out, ref, sizeof(int) * n) == 0);

  /* refused: NULLs, map entries off Y, bad options, a face off the vertices, zero area, NaN */
  CHECK(ss_map_polish(NULL, &Y, rough, NULL, out, &e) == SS_ERR_INVALID);
  CHECK(ss_map_polish(&X, NULL, rough, NULL, out, &e) == SS_ERR_INVALID);
  CHECK(ss_map_polish(&X, &Y, NULL, NULL, out, &e) == SS_ERR_INVALID);
  CHECK(ss_map_polish(&X, &Y, rough, NULL, NULL, &e) == SS_ERR_INVALID);
  memcpy(ref, rough, sizeof(int) * n);
  ref[n / 3] = n;
  CHECK(ss_map_polish(&X, &Y, ref, NULL, out, &e) == SS_ERR_INVALID && strstr(e.msg, "not a vertex of Y"));
  ref[n / 3] = -1;
  CHECK(ss_map_polish(&X, &Y, ref, NULL, out, &e) == SS_ERR_INVALID);
  ss_map_polish_default_options(&o), o.rounds = -1;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_ERR_INVALID);
  ss_map_polish_default_options(&o), o.steps = 0;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_ERR_INVALID);
  ss_map_polish_default_options(&o), o.w_surface_first = 0;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_ERR_INVALID);
  ss_map_polish_default_options(&o), o.w_map_last = NAN;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_ERR_INVALID);
  ss_map_polish_default_options(&o), o.neighbours = 65;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_ERR_INVALID);
  ss_map_polish_default_options(&o), o.min_normal_dot = 1;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_ERR_INVALID);
  ss_map_polish_default_options(&o), o.max_move = 0;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_ERR_INVALID);
  ss_map_polish_default_options(&o), o.mend_mirrored = 2;
  CHECK(ss_map_polish(&X, &Y, rough, &o, out, &e) == SS_ERR_INVALID);
  ss_mesh_free(&Z);
  CHECK(ss_mesh_copy(&Y, &Z, &e) == SS_OK);
  Z.F[7] = Z.nv;
  CHECK(ss_map_polish(&X, &Z, rough, NULL, out, &e) == SS_ERR_INVALID);
  Z.F[7] = Y.F[7];
  for (int i = 0; i < 3 * Z.nv; i++) Z.V[i] = 1.25; /* every vertex at one point: no area */
  CHECK(ss_map_polish(&X, &Z, rough, NULL, out, &e) == SS_ERR_INVALID && strstr(e.msg, "area"));
  memcpy(Z.V, Y.V, sizeof(double) * 3 * (size_t)Z.nv);
  Z.V[5] = NAN;
  CHECK(ss_map_polish(&X, &Z, rough, NULL, out, &e) == SS_ERR_INVALID);

  free(id), free(rough), free(out), free(ref);
  ss_mesh_free(&X), ss_mesh_free(&Y), ss_mesh_free(&Z);
  TEST_MAIN_END();
}
