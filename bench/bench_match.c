/* Matching with segments as probes on FAUST (paper §6, BEST landmarks, ground truth = identity):
 * mean geodesic error of STD, ASA, DIFF and DIFF + ZoomOut over random pairs, and the time of the
 * whole ss_match (both meshes read from files, streamlining and pairing included) and of ZoomOut.
 *   bench_match [--data DIR] [--pairs N] [--seed S] [--k K] [--zoomout KMAX] [--energies E]
 *               [--step S] [--wdescr W] [--wlap W] [--wdcomm W] [--no-timing] [--verbose]
 *               [--zo-pairs N] [--timed-pairs N]   (ZoomOut / whole-match timing on the first N pairs only)
 *               [--profile P] [--wextra W]          (ss_match_options.segment_profile, fmap.w_extra)
 *               [--try SPEC]... [--diag]            (segment-probe experiments, see run_variants below)
 *   bench_match --split tune|held [--lm best|gt] [--pairs N] [--seed S] [--cfg NAME:SPEC]...
 *               held-out protocol (see run_split below): random pairs among FAUST subjects 0-4
 *               (tune, shapes 000-049) or 5-9 (held, 050-099), each ss_match_prepared configuration
 *               on every pair, per-pair errors, means, ratios to the first configuration, CPU s;
 *               [--sel NAME:A,B,C,D:K:W]... the refinement's selection rule applied to configurations
 * Errors: mean over x of d_Y(Π(x), x) / √area(Y), exact geodesics (ss_map_geodesic_error).
 * Accuracy runs reuse one ss_shape_prep per shape (segmentation + 100 eigenpairs); the timed run
 * is a separate, complete ss_match per pair (DIFF, no ZoomOut). */
#include "specseg/fmap.h"
#include "specseg/geodesic.h"
#include "specseg/io.h"
#include "specseg/match.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}
/* The next random pair of distinct FAUST shapes (a, b) from the LCG state *r (the same sequence in
 * every mode of this bench, so its runs compare pair by pair). */
static void next_pair(unsigned *r, int *a, int *b) {
  do {
    *r = *r * 1664525u + 1013904223u;
    *a = (*r >> 8) % 100;
    *r = *r * 1664525u + 1013904223u;
    *b = (*r >> 8) % 100;
  } while (*a == *b);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof(double), cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct slot {
  ss_mesh m;
  ss_shape_prep prep;
  int loaded;
  /* for --try (lazy): exact geodesic fields from every segment centre, on the input (cdist) and on
   * the segmentation's work mesh pulled back through psi (wdist; gdist: its NPP22 graph), n x m,
   * divided by sqrt(area); exact distance to the nearest segment boundary (bdist, n); landmark fields
   * on the input (ldist, n x nl, --diag only) */
  double *cdist, *wdist, *bdist, *gdist, *ldist;
} slot;

static int load(const char *dir, int id, const ss_match_options *o, int kev, slot *s) {
  if (s->loaded) return 0;
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", dir, id);
  ss_error e;
  if (ss_read_mesh(path, &s->m, &e) || ss_shape_prep_compute(&s->m, &o->seg, kev, &s->prep, &e)) {
    fprintf(stderr, "shape %d: %s\n", id, e.msg);
    return 1;
  }
  s->loaded = 1;
  return 0;
}

/* ---- --try SPEC: segment-probe variants against one STD system per pair ----------------------------
 * SPEC is comma-separated key=value: prof=ind|tent|soft|softw|softg|window|erode|gtent|centre|lib,
 * par=P (tent, gtent: radius factor; soft, softw, softg: temperature / sqrt(area), softmin of the
 * distances to all centres on the input / work mesh / work NPP22 graph; window, erode: distance from
 * the segment boundary / sqrt(area); lib: ss_segment_probes with profile P), filt=raw|wave, e=E0:E1:ES (WKS energies of the wave filter, default
 * 0:100:5 = what DIFF uses), norm=col|fn (col: every column normalised, as the library does; fn: a
 * segment's bands keep their energies relative to its strongest band), we=W (data weight relative to
 * w_descr), wc=W (commutativity weight relative to w_dcomm; 0 = data term only), oracle=1 (Y's
 * functions are X's carried by the ground truth: what perfectly consistent segments would give). */
enum { P_IND, P_TENT, P_SOFT, P_SOFTW, P_WINDOW, P_ERODE, P_GTENT, P_CENTRE, P_SOFTG, P_LIB };
typedef struct variant {
  char spec[200];
  int prof, filt, e0, e1, es, fnorm, oracle;
  double par, we, wc, sum;
  int wins;
} variant;

static int parse_variant(const char *spec, variant *v) {
  memset(v, 0, sizeof *v);
  snprintf(v->spec, sizeof v->spec, "%s", spec);
  v->prof = P_TENT, v->par = 1, v->filt = 1, v->e0 = 0, v->e1 = 100, v->es = 5, v->we = 0.5;
  char buf[200];
  snprintf(buf, sizeof buf, "%s", spec);
  for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
    char *eq = strchr(t, '=');
    if (!eq) return 1;
    *eq = 0;
    const char *k = t, *val = eq + 1;
    if (!strcmp(k, "prof")) {
      const char *names[] = {"ind", "tent", "soft", "softw", "window", "erode", "gtent", "centre", "softg", "lib"};
      v->prof = -1;
      for (int i = 0; i < 10; i++)
        if (!strcmp(val, names[i])) v->prof = i;
      if (v->prof < 0) return 1;
    } else if (!strcmp(k, "par")) v->par = atof(val);
    else if (!strcmp(k, "filt")) v->filt = !strcmp(val, "wave");
    else if (!strcmp(k, "e")) {
      if (sscanf(val, "%d:%d:%d", &v->e0, &v->e1, &v->es) != 3) return 1;
    } else if (!strcmp(k, "norm")) v->fnorm = !strcmp(val, "fn");
    else if (!strcmp(k, "we")) v->we = atof(val);
    else if (!strcmp(k, "wc")) v->wc = atof(val);
    else if (!strcmp(k, "oracle")) v->oracle = atoi(val);
    else return 1;
  }
  return v->es < 1 || v->e0 < 0 || v->e1 <= v->e0 || v->e1 > 100 || (v->prof == P_CENTRE && !v->filt);
}

static int shape_fields(slot *s) {
  if (s->cdist) return 0;
  const ss_segmentation *sg = &s->prep.seg;
  const int n = s->m.nv, m = sg->m, nw = sg->work.nv;
  ss_error e;
  ss_geodesic_mesh *gm = NULL, *gw = NULL;
  double *w = malloc(sizeof(double) * (size_t)nw * m);
  s->cdist = malloc(sizeof(double) * (size_t)n * m);
  s->wdist = malloc(sizeof(double) * (size_t)n * m);
  s->bdist = malloc(sizeof(double) * (size_t)n);
  int *src = malloc(sizeof(int) * (size_t)n), ns = 0;
  if (!w || !s->cdist || !s->wdist || !s->bdist || !src) return 1;
  if (ss_geodesic_mesh_build(&s->m, &gm, &e) || ss_geodesic_fields(gm, sg->centers, m, 0, s->cdist, &e) ||
      ss_geodesic_mesh_build(&sg->work, &gw, &e) || ss_geodesic_fields(gw, sg->crit, m, 0, w, &e)) {
    fprintf(stderr, "fields: %s\n", e.msg);
    return 1;
  }
  /* the same on the work mesh's NPP22 graph (Dijkstra) */
  s->gdist = malloc(sizeof(double) * (size_t)n * m);
  double *gw1 = malloc(sizeof(double) * (size_t)nw);
  ss_graph g;
  if (!s->gdist || !gw1 || ss_graph_npp22(&sg->work, &g, &e)) return 1;
  double sw0 = sqrt(ss_mesh_area(&sg->work));
  for (int j = 0; j < m; j++) {
    if (ss_graph_dijkstra(&g, sg->crit + j, 1, 0, gw1, NULL, &e)) return 1;
    for (int x = 0; x < n; x++) s->gdist[x + (size_t)n * j] = sg->psi[x] >= 0 ? gw1[sg->psi[x]] / sw0 : INFINITY;
  }
  ss_graph_free(&g);
  free(gw1);
  double sa = sqrt(s->prep.area), sw = sqrt(ss_mesh_area(&sg->work));
  for (size_t i = 0; i < (size_t)n * m; i++) s->cdist[i] /= sa;
  for (int j = 0; j < m; j++)
    for (int x = 0; x < n; x++)
      s->wdist[x + (size_t)n * j] = sg->psi[x] >= 0 ? w[sg->psi[x] + (size_t)nw * j] / sw : INFINITY;
  /* boundary vertices: an edge to another segment */
  char *isb = calloc((size_t)n, 1);
  for (int f = 0; f < s->m.nf; f++)
    for (int c = 0; c < 3; c++) {
      int a = s->m.F[3 * f + c], b = s->m.F[3 * f + (c + 1) % 3];
      if (sg->labels[a] != sg->labels[b]) isb[a] = isb[b] = 1;
    }
  for (int x = 0; x < n; x++)
    if (isb[x]) src[ns++] = x;
  if (ss_vtp_distances(gm, src, ns, 0, s->bdist, &e)) return 1;
  for (int x = 0; x < n; x++) s->bdist[x] /= sa;
  free(isb), free(src), free(w);
  ss_geodesic_mesh_free(gm), ss_geodesic_mesh_free(gw);
  return 0;
}

/* the probe function of segment seg of shape s (n values) */
static void profile(const slot *s, int seg, const variant *v, double *f) {
  const ss_segmentation *sg = &s->prep.seg;
  const int n = s->m.nv, m = sg->m;
  const double *cd = s->cdist + (size_t)n * seg;
  double R = 0;
  if (v->prof == P_TENT)
    for (int x = 0; x < n; x++)
      if (sg->labels[x] == seg && sg->psi[x] >= 0 && sg->work_dist[sg->psi[x]] > R) R = sg->work_dist[sg->psi[x]];
  if (v->prof == P_GTENT)
    for (int x = 0; x < n; x++)
      if (sg->labels[x] == seg && cd[x] > R) R = cd[x];
  for (int x = 0; x < n; x++) {
    int in = sg->labels[x] == seg;
    double val = 0;
    switch (v->prof) {
    case P_IND: val = in; break;
    case P_TENT: val = in && sg->psi[x] >= 0 && R > 0 ? fmax(0, 1 - sg->work_dist[sg->psi[x]] / (v->par * R)) : 0; break;
    case P_GTENT: val = R > 0 ? fmax(0, 1 - cd[x] / (v->par * R)) : 0; break;
    case P_WINDOW: val = in ? fmin(1, s->bdist[x] / v->par) : 0; break;
    case P_ERODE: val = in && s->bdist[x] > v->par; break;
    case P_SOFT:
    case P_SOFTW:
    case P_SOFTG: {
      const double *D = v->prof == P_SOFT ? s->cdist : v->prof == P_SOFTW ? s->wdist : s->gdist;
      const double *ds = D + (size_t)n * seg;
      double dmin = INFINITY, z = 0;
      for (int j = 0; j < m; j++) dmin = fmin(dmin, D[x + (size_t)n * j]);
      for (int j = 0; j < m; j++) z += exp(-(D[x + (size_t)n * j] - dmin) / v->par);
      val = isfinite(ds[x]) ? exp(-(ds[x] - dmin) / v->par) / z : 0;
      break;
    }
    default: break;
    }
    f[x] = val;
  }
}

/* extra probes of one shape: np segments (segs) of shape s, functions taken from shape fs (fs = s,
 * or X for the oracle on Y) */
static int variant_probes(const slot *s, const slot *fs, int np, const int *segs, const variant *v, int k,
                          ss_fmap_probes *out) {
  const int n = s->m.nv, nb = v->filt ? (v->e1 - v->e0 + v->es - 1) / v->es : 1, p = np * nb;
  const double *ev = s->prep.evecs, *M = s->prep.M;
  double *f = malloc(sizeof(double) * (size_t)n * np), *F = malloc(sizeof(double) * (size_t)n * p);
  double *a = malloc(sizeof(double) * (size_t)k * np), *G = malloc(sizeof(double) * 100 * (size_t)k);
  double *c = malloc(sizeof(double) * (size_t)k);
  ss_error e;
  if (!f || !F || !a || !G || !c) return 1;
  for (int q = 0; q < np; q++) {
    if (v->prof == P_CENTRE) {
      int cv = fs->prep.seg.centers[segs[q]];
      for (int i = 0; i < k; i++) a[i + (size_t)k * q] = ev[cv + (size_t)n * i];
    } else if (v->prof != P_LIB) profile(fs, segs[q], v, f + (size_t)n * q);
  }
  if (v->prof == P_LIB) { /* the library's ss_segment_probes, profile par */
    double *E = NULL;
    if (ss_segment_probes(&fs->prep.seg, np, segs, (int)v->par, &E, &e)) return 1;
    memcpy(f, E, sizeof(double) * (size_t)n * np);
    free(E);
  }
  if (v->prof != P_CENTRE && ss_fmap_project(n, k, ev, M, np, f, a, &e)) return 1;
  if (v->filt && ss_wks_filters(s->prep.evals, k, 100, 7.0, G, &e)) return 1;
  for (int q = 0; q < np; q++) {
    double mx = 0, *nrm = malloc(sizeof(double) * nb);
    for (int b = 0; b < nb; b++) {
      double *col = F + (size_t)n * (q * nb + b);
      if (!v->filt) memcpy(col, f + (size_t)n * q, sizeof(double) * n);
      else {
        int j = v->e0 + b * v->es;
        for (int i = 0; i < k; i++) c[i] = G[j + 100 * (size_t)i] * a[i + (size_t)k * q];
        for (int x = 0; x < n; x++) {
          double t = 0;
          for (int i = 0; i < k; i++) t += ev[x + (size_t)n * i] * c[i];
          col[x] = t;
        }
      }
      double s2 = 0;
      for (int x = 0; x < n; x++) s2 += M[x] * col[x] * col[x];
      nrm[b] = sqrt(s2);
      mx = fmax(mx, nrm[b]);
    }
    for (int b = 0; b < nb; b++) {
      double sc = v->fnorm ? (mx > 0 ? 1 / mx : 0) : (nrm[b] > 1e-12 * mx ? 1 / nrm[b] : 0);
      double *col = F + (size_t)n * (q * nb + b);
      for (int x = 0; x < n; x++) col[x] *= sc;
    }
    free(nrm);
  }
  memset(out, 0, sizeof *out);
  out->k = k, out->p = p, out->nd = v->wc > 0 ? p : 0;
  out->A = malloc(sizeof(double) * (size_t)k * p);
  if (!out->A || ss_fmap_project(n, k, ev, M, p, F, out->A, &e)) return 1;
  if (out->nd) {
    size_t kk = (size_t)k * (k + 1) / 2;
    out->P = malloc(sizeof(double) * kk * p);
    if (!out->P || ss_fmap_mult_operators_packed(n, k, ev, M, p, F, out->P, &e)) return 1;
    /* the commutativity term is quadratic in the operators: sqrt(wc) gives it weight wc·w_dcomm */
    for (size_t i = 0; i < kk * p; i++) out->P[i] *= sqrt(v->wc);
  }
  free(f), free(F), free(a), free(G), free(c);
  return 0;
}

static int run_variants(const char *dir, unsigned seed, int npairs, int nl, const int *lm, const ss_match_options *o,
                        int nv, variant *V, int diag) {
  slot *S = calloc(100, sizeof(slot));
  const int k = o->fmap.k;
  ss_fmap_match_options fo = o->fmap;
  fo.zoomout_kmax = 0;
  double sum_std = 0;
  unsigned r = seed;
  printf("variants (k %d, weights %g %g %g):\n", k, fo.w_descr, fo.w_lap, fo.w_dcomm);
  for (int i = 0; i < nv; i++) printf("  v%d: %s\n", i, V[i].spec);
  for (int p = 0; p < npairs; p++) {
    int a, b;
    next_pair(&r, &a, &b);
    if (load(dir, a, o, k, &S[a]) || load(dir, b, o, k, &S[b]) || shape_fields(&S[a]) || shape_fields(&S[b])) return 1;
    const int trilat = diag;
    for (int t = 0; trilat && t < 2; t++) { /* landmark fields on the input, for the diagnostic */
      slot *sl = &S[t ? b : a];
      if (sl->ldist) continue;
      ss_geodesic_mesh *gm = NULL;
      ss_error e2;
      sl->ldist = malloc(sizeof(double) * (size_t)sl->m.nv * nl);
      if (!sl->ldist || ss_geodesic_mesh_build(&sl->m, &gm, &e2) || ss_geodesic_fields(gm, lm, nl, 0, sl->ldist, &e2))
        return 1;
      ss_geodesic_mesh_free(gm);
      for (size_t i = 0; i < (size_t)sl->m.nv * nl; i++) sl->ldist[i] /= sqrt(sl->prep.area);
    }
    const slot *X = &S[a], *Y = &S[b];
    ss_error e;
    ss_segment_pairs pr;
    ss_fmap_shape sX = {&X->m, X->prep.M, X->prep.evals, X->prep.evecs, X->prep.kev, NULL, 0, NULL, 0};
    ss_fmap_shape sY = {&Y->m, Y->prep.M, Y->prep.evals, Y->prep.evecs, Y->prep.kev, NULL, 0, NULL, 0};
    ss_fmap_probes bX, bY;
    ss_fmap_weights w;
    ss_fmap_system *sys = NULL;
    int *map = malloc(sizeof(int) * (size_t)X->m.nv);
    double *Ck = malloc(sizeof(double) * (size_t)k * k), err_std;
    if (ss_pair_segments(&X->prep.seg, &Y->prep.seg, nl, lm, lm, &pr, &e) ||
        ss_fmap_base_probes(&sX, nl, lm, &fo, fo.w_dcomm > 0, &bX, &e) ||
        ss_fmap_base_probes(&sY, nl, lm, &fo, fo.w_dcomm > 0, &bY, &e) || ss_fmap_pair_weights(&sX, &sY, &fo, &w, &e) ||
        ss_fmap_system_new(k, k, Y->prep.evals, X->prep.evals, &bY, &bX, &w, &sys, &e) ||
        ss_fmap_system_solve(sys, NULL, NULL, 0, 0, Ck, &e) || ss_fmap_match_finish(&sX, &sY, &fo, Ck, map, NULL, &e) ||
        ss_map_geodesic_error(&Y->m, X->m.nv, map, NULL, NULL, NULL, &err_std, &e)) {
      fprintf(stderr, "pair %d-%d: %s\n", a, b, e.msg);
      return 1;
    }
    sum_std += err_std;
    if (diag && X->m.nv == Y->m.nv) { /* per segment pair: area IoU under the ground truth, centre error */
      printf("diag %3d -> %3d:", a, b);
      for (int q = 0; q < pr.n; q++) {
        double in = 0, un = 0;
        for (int x = 0; x < X->m.nv; x++) {
          int u = X->prep.seg.labels[x] == pr.sx[q], w2 = Y->prep.seg.labels[x] == pr.sy[q];
          in += (u && w2) * Y->prep.M[x], un += (u || w2) * Y->prep.M[x];
        }
        int cx = X->prep.seg.centers[pr.sx[q]];
        int near = -1;
        for (int l = 0; l < nl; l++)
          if (X->cdist[lm[l] + (size_t)X->m.nv * pr.sx[q]] < 0.25 &&
              (near < 0 || X->cdist[lm[l] + (size_t)X->m.nv * pr.sx[q]] < X->cdist[lm[near] + (size_t)X->m.nv * pr.sx[q]]))
            near = l;
        /* trilateration diagnostic: the vertex of Y whose landmark distances best match c_X's */
        double tri = NAN;
        if (trilat) {
          double best = INFINITY;
          int yb = -1;
          for (int y = 0; y < Y->m.nv; y++) {
            double e2 = 0;
            for (int l = 0; l < nl; l++) {
              double dd = Y->ldist[y + (size_t)Y->m.nv * l] - X->ldist[cx + (size_t)X->m.nv * l];
              e2 += dd * dd;
            }
            if (e2 < best) best = e2, yb = y;
          }
          ss_geodesic_mesh *gmy = NULL;
          ss_error e3;
          if (!ss_geodesic_mesh_build(&Y->m, &gmy, &e3)) ss_geodesic_pairs(gmy, NULL, &yb, &cx, 1, &tri, &e3);
          ss_geodesic_mesh_free(gmy);
          tri /= sqrt(Y->prep.area);
        }
        printf(" [L%d %d-%d %.2f %.3f %.3f t%.3f]", near, pr.sx[q], pr.sy[q], un > 0 ? in / un : 0, Y->cdist[cx + (size_t)Y->m.nv * pr.sy[q]], pr.energy[q], tri);
      }
      printf("\n");
    }
    printf("pair %2d: %3d -> %3d paired %d  STD %.4f", p, a, b, pr.n, err_std);
    for (int i = 0; i < nv; i++) {
      ss_fmap_probes xX, xY;
      double err_v;
      if (variant_probes(X, X, pr.n, pr.sx, &V[i], k, &xX) ||
          variant_probes(Y, V[i].oracle ? X : Y, pr.n, V[i].oracle ? pr.sx : pr.sy, &V[i], k, &xY) ||
          ss_fmap_system_solve(sys, &xY, &xX, V[i].we, V[i].wc > 0, Ck, &e) ||
          ss_fmap_match_finish(&sX, &sY, &fo, Ck, map, NULL, &e) ||
          ss_map_geodesic_error(&Y->m, X->m.nv, map, NULL, NULL, NULL, &err_v, &e)) {
        fprintf(stderr, "pair %d-%d v%d: %s\n", a, b, i, e.msg);
        return 1;
      }
      V[i].sum += err_v;
      V[i].wins += err_v < err_std;
      printf("  v%d %.4f", i, err_v);
      ss_fmap_probes_free(&xX), ss_fmap_probes_free(&xY);
    }
    printf("\n");
    fflush(stdout);
    ss_fmap_system_free(sys);
    ss_fmap_probes_free(&bX), ss_fmap_probes_free(&bY);
    ss_segment_pairs_free(&pr);
    free(map), free(Ck);
  }
  printf("mean over %d pairs (seed %u): STD %.4f\n", npairs, seed, sum_std / npairs);
  for (int i = 0; i < nv; i++)
    printf("  v%d %.4f  x STD %.3f  better on %d/%d  [%s]\n", i, V[i].sum / npairs, V[i].sum / sum_std, V[i].wins,
           npairs, V[i].spec);
  for (int i = 0; i < 100; i++)
    if (S[i].loaded) {
      ss_shape_prep_free(&S[i].prep), ss_mesh_free(&S[i].m);
      free(S[i].cdist), free(S[i].wdist), free(S[i].bdist), free(S[i].gdist), free(S[i].ldist);
    }
  free(S);
  return 0;
}

/* ---- --split: configurations of ss_match_prepared on a named pair set ---------------------------
 * Pairs: next_pair's LCG from --seed, both shapes in [lo, lo + 50) (tune: subjects 0-4, held:
 * subjects 5-9), distinct. Landmarks: BEST (landmarks_best.txt) or GT-like (landmarks_gt_authors.txt,
 * the authors' FPS set; identity ground truth makes it valid on every shape). Each --cfg NAME:SPEC
 * is ss_match_default_options changed by SPEC, comma-separated key=value:
 *   paper=1 (start from ss_match_paper_options instead), probes=std|asa|diff, k=K, dk=DESCR_K,
 *   zo=KMAX (fmap.zoomout_kmax), zstep=S, zs=N (fmap.zoomout_samples), single=0|1 (refine_single),
 *   prof=0|1|2, wextra=W, orient=W (fmap.w_orient), refine=none|zo|best, wlap=W
 *   (refine_w_lap), pair=paper|default, ratio=R, mutual=0|1, rel=E, minlm=N (pairing options)
 * Without --cfg: the paper's STD and DIFF (unrefined, descr_k = k) and the library's default. CPU: process CPU seconds of the
 * ss_match_prepared call (all threads), shapes prepared beforehand and not counted. */
typedef struct config {
  char name[32], spec[200];
  ss_match_options o;
  double sum, cpu;
  int wins; /* pairs where it is below the first configuration */
} config;

static int apply_spec(const char *spec, ss_match_options *o) {
  char buf[200];
  snprintf(buf, sizeof buf, "%s", spec);
  for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
    char *eq = strchr(t, '=');
    if (!eq) return 1;
    *eq = 0;
    const char *k = t, *v = eq + 1;
    if (!strcmp(k, "probes")) {
      if (!strcmp(v, "std")) o->probes = SS_PROBES_STD;
      else if (!strcmp(v, "asa")) o->probes = SS_PROBES_ASA;
      else if (!strcmp(v, "diff")) o->probes = SS_PROBES_DIFF;
      else return 1;
    } else if (!strcmp(k, "paper")) {
      if (atoi(v)) ss_match_paper_options(o);
    } else if (!strcmp(k, "refine")) {
      if (!strcmp(v, "none")) o->refine = SS_REFINE_NONE;
      else if (!strcmp(v, "zo")) o->refine = SS_REFINE_ZOOMOUT;
      else if (!strcmp(v, "best")) o->refine = SS_REFINE_BEST;
      else return 1;
    } else if (!strcmp(k, "pair")) {
      if (!strcmp(v, "paper")) ss_pairing_paper_options(&o->pairing);
      else if (!strcmp(v, "default")) ss_pairing_default_options(&o->pairing);
      else return 1;
    } else if (!strcmp(k, "ratio")) o->pairing.min_ratio = atof(v);
    else if (!strcmp(k, "mutual")) o->pairing.mutual = atoi(v);
    else if (!strcmp(k, "rel")) o->pairing.max_rel_energy = atof(v);
    else if (!strcmp(k, "minlm")) o->pairing.min_landmarks = atoi(v);
    else if (!strcmp(k, "wlap")) o->refine_w_lap = atof(v);
    else if (!strcmp(k, "zstep")) o->fmap.zoomout_step = atoi(v);
    else if (!strcmp(k, "k")) o->fmap.k = atoi(v);
    else if (!strcmp(k, "dk")) o->fmap.descr_k = atoi(v);
    else if (!strcmp(k, "zo")) o->fmap.zoomout_kmax = atoi(v);
    else if (!strcmp(k, "prof")) o->segment_profile = (ss_segment_profile)atoi(v);
    else if (!strcmp(k, "wextra")) o->fmap.w_extra = atof(v);
    else if (!strcmp(k, "zs")) o->fmap.zoomout_samples = atoi(v);
    else if (!strcmp(k, "single")) o->refine_single = atoi(v);
    else if (!strcmp(k, "orient")) o->fmap.w_orient = atof(v);
    else return 1;
  }
  return 0;
}

static int parse_config(const char *arg, config *c) {
  memset(c, 0, sizeof *c);
  const char *colon = strchr(arg, ':');
  if (!colon || colon == arg || colon - arg >= (long)sizeof c->name) return 1;
  memcpy(c->name, arg, (size_t)(colon - arg));
  snprintf(c->spec, sizeof c->spec, "%s", colon + 1);
  ss_match_default_options(&c->o);
  return *c->spec && apply_spec(c->spec, &c->o);
}

static double process_cpu(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int config_kev(const ss_match_options *o) {
  int kev = o->fmap.k;
  if (o->refine != SS_REFINE_NONE && o->fmap.zoomout_kmax > kev) kev = o->fmap.zoomout_kmax;
  if (o->fmap.descr_k > kev) kev = o->fmap.descr_k;
  return kev;
}

/* --sel NAME:A,B,C,D:K:W:WD — the refined default's rule applied afterwards to the maps of
 * configurations A (STD start), B (its refinement), C (segment-aided start), D (its refinement)
 * (0-based --cfg indices): lowest ss_p2p_energy (k0 = k of A, size K, w_lap W) + WD x
 * ss_p2p_descr_residual (A's base probes at its k), a refinement only when not above its own start.
 * Equals SS_REFINE_BEST when the configurations are its candidates, at no extra cost. */
typedef struct selection {
  char name[32];
  int c[4], K;
  double w, wd, sum, right, cmp;
  int counts[4];
} selection;

static int parse_selection(const char *arg, selection *s) {
  memset(s, 0, sizeof *s);
  char nm[32];
  if (sscanf(arg, "%31[^:]:%d,%d,%d,%d:%d:%lf:%lf", nm, &s->c[0], &s->c[1], &s->c[2], &s->c[3], &s->K, &s->w, &s->wd) != 8)
    return 1;
  snprintf(s->name, sizeof s->name, "%s", nm);
  return s->K < 3 || s->w < 0 || s->wd < 0;
}

static int run_split(const char *dir, const char *split, const char *lmname, unsigned seed, int npairs, config *cf,
                     int ncf, selection *sel, int nsel) {
  const int lo = !strcmp(split, "tune") ? 0 : !strcmp(split, "held") ? 50 : -1;
  if (lo < 0 || (strcmp(lmname, "best") && strcmp(lmname, "gt"))) {
    fprintf(stderr, "--split tune|held, --lm best|gt\n");
    return 2;
  }
  int *lm = NULL, nl = 0;
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/%s", dir, !strcmp(lmname, "best") ? "landmarks_best.txt" : "landmarks_gt_authors.txt");
  ss_error e;
  if (ss_read_ints(path, &lm, &nl, &e)) {
    fprintf(stderr, "landmarks: %s\n", e.msg);
    return 1;
  }
  int kev = 0;
  for (int c = 0; c < ncf; c++)
    if (config_kev(&cf[c].o) > kev) kev = config_kev(&cf[c].o);
  printf("FAUST split %s (shapes %03d-%03d), %d pairs, seed %u, %s landmarks (%d), eigenpairs %d\n", split, lo, lo + 49,
         npairs, seed, lmname, nl, kev);
  for (int c = 0; c < ncf; c++) printf("  %-10s %s\n", cf[c].name, cf[c].spec[0] ? cf[c].spec : "(defaults)");
  for (int q = 0; q < nsel; q++)
    for (int i = 0; i < 4; i++)
      if (sel[q].c[i] < 0 || sel[q].c[i] >= ncf) { fprintf(stderr, "--sel %s: no configuration %d\n", sel[q].name, sel[q].c[i]); return 2; }
  for (int q = 0; q < nsel; q++) if (sel[q].K > kev) kev = sel[q].K;
  slot *S = calloc(100, sizeof(slot));
  double *errs = malloc(sizeof(double) * (size_t)ncf);
  int **maps = calloc((size_t)ncf, sizeof(int *));
  unsigned r = seed;
  ss_match_options so;
  ss_match_default_options(&so);
  for (int p = 0; p < npairs; p++) {
    int a, b;
    do next_pair(&r, &a, &b);
    while (a / 50 != lo / 50 || b / 50 != lo / 50);
    if (load(dir, a, &so, kev, &S[a]) || load(dir, b, &so, kev, &S[b])) return 1;
    printf("pair %2d: %3d -> %3d", p, a, b);
    for (int c = 0; c < ncf; c++) {
      ss_match_result res;
      double c0 = process_cpu();
      if (ss_match_prepared(&S[a].prep, &S[b].prep, nl, lm, lm, &cf[c].o, &res, &e)) {
        fprintf(stderr, "pair %d-%d %s: %s\n", a, b, cf[c].name, e.msg);
        return 1;
      }
      cf[c].cpu += process_cpu() - c0;
      if (ss_map_geodesic_error(&S[b].m, res.nX, res.map, NULL, NULL, NULL, &errs[c], &e)) {
        fprintf(stderr, "pair %d-%d: %s\n", a, b, e.msg);
        return 1;
      }
      cf[c].sum += errs[c];
      cf[c].wins += errs[c] < errs[0];
      printf("  %s %.4f", cf[c].name, errs[c]);
      if (res.refine_choice >= 0) printf(" [%c%s]", res.refine_choice < 2 ? 'S' : 'D', res.refine_choice & 1 ? "+ZO" : "");
      free(maps[c]);
      maps[c] = res.map;
      res.map = NULL;
      ss_match_result_free(&res);
    }
    const ss_shape_prep *pX = &S[a].prep, *pY = &S[b].prep;
    for (int q = 0; q < nsel; q++) {
      double E[4], best = INFINITY, R = 0;
      int ch = -1;
      const ss_fmap_match_options *fo = &cf[sel[q].c[0]].o.fmap;
      ss_fmap_shape sX = {&S[a].m, pX->M, pX->evals, pX->evecs, pX->kev, NULL, 0, NULL, 0}, sY = {&S[b].m, pY->M, pY->evals, pY->evecs, pY->kev, NULL, 0, NULL, 0};
      ss_fmap_probes bX = {0}, bY = {0};
      if (sel[q].wd > 0 &&
          (ss_fmap_base_probes(&sX, nl, lm, fo, 0, &bX, &e) || ss_fmap_base_probes(&sY, nl, lm, fo, 0, &bY, &e))) {
        fprintf(stderr, "probes: %s\n", e.msg);
        return 1;
      }
      for (int i = 0; i < 4; i++) {
        if (ss_p2p_energy(pY->mesh->nv, pX->mesh->nv, pY->evals, pX->evals, pY->evecs, pX->evecs, pX->M, maps[sel[q].c[i]],
                          fo->k, sel[q].K, 1, sel[q].w, &E[i], NULL, NULL, &e) ||
            (sel[q].wd > 0 && ss_p2p_descr_residual(pY->mesh->nv, pX->mesh->nv, pY->evecs, pX->evecs, pX->M, &bY, &bX,
                                                    maps[sel[q].c[i]], &R, &e))) {
          fprintf(stderr, "energy: %s\n", e.msg);
          return 1;
        }
        E[i] += sel[q].wd * R;
      }
      ss_fmap_probes_free(&bX), ss_fmap_probes_free(&bY);
      for (int i = 0; i < 4; i++)
        if (E[i] < best && (!(i & 1) || E[i] <= E[i - 1])) best = E[i], ch = i;
      double ev = errs[sel[q].c[ch]];
      sel[q].sum += ev;
      sel[q].counts[ch]++;
      /* did it pick the better of the two refined maps (B, D)? */
      double eb = errs[sel[q].c[1]], ed = errs[sel[q].c[3]];
      int pick_d = E[3] < E[1];
      if (eb != ed) sel[q].cmp++, sel[q].right += (pick_d == (ed < eb));
      printf("  %s %.4f [%d]", sel[q].name, ev, ch);
    }
    printf("\n");
    fflush(stdout);
  }
  printf("split %s, %s landmarks, %d pairs, seed %u: mean error, x %s, better than %s on, CPU s/pair\n", split, lmname,
         npairs, seed, cf[0].name, cf[0].name);
  for (int c = 0; c < ncf; c++)
    printf("  %-10s %.4f  x %.3f  %2d/%d  %.3f s\n", cf[c].name, cf[c].sum / npairs, cf[c].sum / cf[0].sum, cf[c].wins,
           npairs, cf[c].cpu / npairs);
  for (int q = 0; q < nsel; q++)
    printf("  %-10s %.4f  x %.3f  (choices S %d, S+ZO %d, D %d, D+ZO %d; energy picks the better of the two refined maps on "
           "%.0f/%.0f pairs where they differ)\n",
           sel[q].name, sel[q].sum / npairs, sel[q].sum / cf[0].sum, sel[q].counts[0], sel[q].counts[1], sel[q].counts[2],
           sel[q].counts[3], sel[q].right, sel[q].cmp);
  for (int i = 0; i < 100; i++)
    if (S[i].loaded) ss_shape_prep_free(&S[i].prep), ss_mesh_free(&S[i].m);
  for (int c = 0; c < ncf; c++) free(maps[c]);
  free(S), free(errs), free(lm), free(maps);
  return 0;
}

int main(int argc, char **argv) {
  const char *dir = SS_DATA_DIR_DEFAULT;
  int npairs = 30, timing = 1, verbose = 0, zo_pairs = 1 << 30, timed_pairs = 1 << 30;
  unsigned seed = 7;
  ss_match_options o;
  ss_match_paper_options(&o); /* the paper's STD / ASA / DIFF; DIFF+ZO: ZoomOut of DIFF alone */
  o.fmap.zoomout_kmax = 100;
  variant var[64];
  int nvar = 0, diag = 0, ncf = 0;
  const char *split = NULL, *lmname = "best";
  static config cf[32];
  static selection sel[16];
  int nsel = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "0";
    if (!strcmp(a, "--data")) dir = v, i++;
    else if (!strcmp(a, "--pairs")) npairs = atoi(v), i++;
    else if (!strcmp(a, "--seed")) seed = (unsigned)atoi(v), i++;
    else if (!strcmp(a, "--k")) o.fmap.k = atoi(v), i++;
    else if (!strcmp(a, "--zoomout")) o.fmap.zoomout_kmax = atoi(v), i++;
    else if (!strcmp(a, "--energies")) o.fmap.n_energies = atoi(v), i++;
    else if (!strcmp(a, "--step")) o.fmap.descr_step = atoi(v), i++;
    else if (!strcmp(a, "--wdescr")) o.fmap.w_descr = atof(v), i++;
    else if (!strcmp(a, "--wlap")) o.fmap.w_lap = atof(v), i++;
    else if (!strcmp(a, "--wdcomm")) o.fmap.w_dcomm = atof(v), i++;
    else if (!strcmp(a, "--profile")) o.segment_profile = (ss_segment_profile)atoi(v), i++;
    else if (!strcmp(a, "--wextra")) o.fmap.w_extra = atof(v), i++;
    else if (!strcmp(a, "--no-timing")) timing = 0;
    else if (!strcmp(a, "--zo-pairs")) zo_pairs = atoi(v), i++;
    else if (!strcmp(a, "--timed-pairs")) timed_pairs = atoi(v), i++;
    else if (!strcmp(a, "--verbose")) verbose = 1;
    else if (!strcmp(a, "--diag")) diag = 1;
    else if (!strcmp(a, "--split")) split = v, i++;
    else if (!strcmp(a, "--lm")) lmname = v, i++;
    else if (!strcmp(a, "--sel") && nsel < 16) {
      if (parse_selection(v, &sel[nsel++])) { fprintf(stderr, "bad --sel %s\n", v); return 2; }
      i++;
    }
    else if (!strcmp(a, "--cfg") && ncf < 32) {
      if (parse_config(v, &cf[ncf++])) { fprintf(stderr, "bad --cfg %s\n", v); return 2; }
      i++;
    }
    else if (!strcmp(a, "--try") && nvar < 64) {
      if (parse_variant(v, &var[nvar++])) { fprintf(stderr, "bad --try %s\n", v); return 2; }
      i++;
    }
    else { fprintf(stderr, "unknown option %s\n", a); return 2; }
  }
  if (npairs < 1 || o.fmap.k < 3 || (o.fmap.zoomout_kmax && o.fmap.zoomout_kmax < o.fmap.k)) {
    fprintf(stderr, "bad options\n");
    return 2;
  }
  if (split) {
    if (!ncf) {
      const char *def[3] = {"STD:paper=1,probes=std", "DIFF:paper=1,probes=diff", "default:"};
      for (int c = 0; c < 3; c++) parse_config(def[c], &cf[c]);
      ncf = 3;
    }
    return run_split(dir, split, lmname, seed, npairs, cf, ncf, sel, nsel);
  }
  int *lm = NULL, nl = 0;
  {
    char path[4096];
    snprintf(path, sizeof path, "%s/faust/landmarks_best.txt", dir);
    ss_error e;
    if (ss_read_ints(path, &lm, &nl, &e)) {
      fprintf(stderr, "landmarks: %s\n", e.msg);
      return 1;
    }
  }
  if (nvar) {
    int rc = run_variants(dir, seed, npairs, nl, lm, &o, nvar, var, diag);
    free(lm);
    return rc;
  }
  int kev = o.fmap.zoomout_kmax > o.fmap.k ? o.fmap.zoomout_kmax : o.fmap.k;
  slot *S = calloc(100, sizeof(slot));
  double sum[4] = {0}, *tmatch = calloc((size_t)npairs, sizeof(double)), *tzoom = calloc((size_t)npairs, sizeof(double));
  double *cmatch = calloc((size_t)npairs, sizeof(double));
  double *tpair = calloc((size_t)npairs, sizeof(double)), *tfmap = calloc((size_t)npairs, sizeof(double));
  int better = 0, npaired = 0, nzo = 0, ntimed = 0;
  double sum_diff_zo = 0;
  const char *names[4] = {"STD", "ASA", "DIFF", "DIFF+ZO"};
  printf("FAUST, %d pairs (seed %u), %d BEST landmarks, k %d, ZoomOut %d, energies %d step %d, weights %g %g %g, "
         "segment profile %d, w_extra %g\n",
         npairs, seed, nl, o.fmap.k, o.fmap.zoomout_kmax, o.fmap.n_energies, o.fmap.descr_step, o.fmap.w_descr,
         o.fmap.w_lap, o.fmap.w_dcomm, o.segment_profile, o.fmap.w_extra);
  unsigned r = seed;
  for (int p = 0; p < npairs; p++) {
    int a, b;
    next_pair(&r, &a, &b);
    if (load(dir, a, &o, kev, &S[a]) || load(dir, b, &o, kev, &S[b])) return 1;
    double err4[4];
    ss_error e;
    for (int v = 0; v < 4; v++) {
      ss_match_options ov = o;
      ov.probes = v == 0 ? SS_PROBES_STD : v == 1 ? SS_PROBES_ASA : SS_PROBES_DIFF;
      if (v < 3) ov.fmap.zoomout_kmax = 0;
      else ov.refine = SS_REFINE_ZOOMOUT;
      if (v == 3 && (o.fmap.zoomout_kmax <= o.fmap.k || p >= zo_pairs)) { err4[3] = NAN; continue; }
      ss_match_result res;
      if (ss_match_prepared(&S[a].prep, &S[b].prep, nl, lm, lm, &ov, &res, &e) ||
          ss_map_geodesic_error(&S[b].m, res.nX, res.map, NULL, NULL, NULL, &err4[v], &e)) {
        fprintf(stderr, "pair %d-%d %s: %s\n", a, b, names[v], e.msg);
        return 1;
      }
      if (v == 3) tzoom[p] = res.t_zoomout;
      if (v == 2) {
        npaired = res.pairs.n;
        tpair[p] = res.t_pair;
        tfmap[p] = res.t_fmap;
      }
      ss_match_result_free(&res);
    }
    for (int v = 0; v < 3; v++) sum[v] += err4[v];
    if (!isnan(err4[3])) sum[3] += err4[3], sum_diff_zo += err4[2], nzo++;
    better += err4[2] < err4[0];
    if (timing && p < timed_pairs) { /* the whole pipeline from the files, nothing cached */
      char pa[4096], pb[4096];
      snprintf(pa, sizeof pa, "%s/faust/tr_reg_%03d.off", dir, a);
      snprintf(pb, sizeof pb, "%s/faust/tr_reg_%03d.off", dir, b);
      ss_match_options ot = o;
      ot.probes = SS_PROBES_DIFF;
      ot.fmap.zoomout_kmax = 0;
      double t0 = ss_time(), c0 = (double)clock() / CLOCKS_PER_SEC;
      ss_mesh X = {0}, Y = {0};
      ss_match_result res;
      if (ss_read_mesh(pa, &X, &e) || ss_read_mesh(pb, &Y, &e) || ss_match(&X, &Y, nl, lm, lm, &ot, &res, &e)) {
        fprintf(stderr, "timed pair %d-%d: %s\n", a, b, e.msg);
        return 1;
      }
      tmatch[ntimed] = ss_time() - t0;
      cmatch[ntimed++] = (double)clock() / CLOCKS_PER_SEC - c0;
      if (verbose)
        fprintf(stderr, "  timed: segment %.3f eigs %.3f pair %.3f fmap %.3f total %.3f\n", res.t_segment, res.t_eigs,
                res.t_pair, res.t_fmap, tmatch[ntimed - 1]);
      ss_match_result_free(&res);
      ss_mesh_free(&X);
      ss_mesh_free(&Y);
    }
    printf("pair %2d: %3d -> %3d  segs %2d/%2d paired %2d  STD %.4f ASA %.4f DIFF %.4f DIFF+ZO %.4f  match %.3f s "
           "zoomout %.3f s\n",
           p, a, b, S[a].prep.seg.m, S[b].prep.seg.m, npaired, err4[0], err4[1], err4[2], err4[3],
           timing && p < timed_pairs ? tmatch[ntimed - 1] : 0.0, tzoom[p]);
    fflush(stdout);
  }
  printf("mean error over %d pairs:", npairs);
  for (int v = 0; v < 3; v++) printf("  %s %.4f", names[v], sum[v] / npairs);
  if (nzo) printf("\nover the first %d pairs: DIFF %.4f, DIFF+ZoomOut %.4f", nzo, sum_diff_zo / nzo, sum[3] / nzo);
  printf("\nDIFF/STD %.3f (goal <= 0.8), ASA/STD %.3f (goal <= 1); DIFF better than STD on %d of %d pairs\n",
         sum[2] / sum[0], sum[1] / sum[0], better, npairs);
  printf("reference: pyFM STD 0.046, pyFM ZoomOut 0.030; paper STD 0.027, DIFF 0.020\n");
  printf("median pairing %.3f s, fmap (k %d) %.3f s\n", median(tpair, npairs), o.fmap.k, median(tfmap, npairs));
  if (timing && ntimed) printf("median whole ss_match (files in, DIFF) over %d pairs %.3f s wall, %.3f s CPU (goal <= 1 s; pyFM ~10 s)\n", ntimed, median(tmatch, ntimed), median(cmatch, ntimed));
  if (nzo) printf("median ZoomOut %d -> %d: %.3f s (goal < 3 s; pyFM ~58 s)\n", o.fmap.k, o.fmap.zoomout_kmax,
         median(tzoom, nzo));
  for (int i = 0; i < 100; i++)
    if (S[i].loaded) ss_shape_prep_free(&S[i].prep), ss_mesh_free(&S[i].m);
  free(S), free(lm), free(tmatch), free(tzoom), free(tpair), free(tfmap), free(cmatch);
  return 0;
}
