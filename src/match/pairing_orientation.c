/* The left / right (orientation) tests of a pairing: the orientation score of a point map against the
 * shapes' outward normals (whole map and per segment, the median margin between two maps), the map
 * of a small functional map with the paired centres as landmarks (ss_fmap_match), and the same with
 * probes shared by the candidates (ssi_orient_ctx), which the decision and the self-symmetry use. */
#include "specseg/fmap.h"
#include "match/autopair_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The orientation score of T over A's faces (those of segments in segmask, NULL: all) and, in seg (A->m,
 * may be NULL), that of each segment's faces (a face belongs to its first vertex's segment; NAN for a
 * segment without a counted face). */
static double map_orientation_seg(const ss_centre_signature *A, const ss_centre_signature *B, const int *T,
                                  const int *segmask, double *seg) {
  const ss_mesh *mA = A->prep->mesh, *mB = B->prep->mesh;
  const int *lab = A->prep->seg.labels, m = A->m;
  double pos = 0, tot = 0;
  if (seg)
    for (int a = 0; a < 2 * m; a++) seg[a] = 0; /* scratch: m counts then m positives, see below */
  double *cnt = seg, *cpos = seg ? seg + m : NULL;
  for (int f = 0; f < mA->nf; f++) {
    const int *t = mA->F + 3 * (size_t)f;
    if (segmask && !(segmask[lab[t[0]]] && segmask[lab[t[1]]] && segmask[lab[t[2]]])) continue;
    const double *q0 = mB->V + 3 * (size_t)T[t[0]], *q1 = mB->V + 3 * (size_t)T[t[1]], *q2 = mB->V + 3 * (size_t)T[t[2]];
    const double *nr = B->normals + 3 * (size_t)T[t[0]];
    double u[3] = {q1[0] - q0[0], q1[1] - q0[1], q1[2] - q0[2]}, w[3] = {q2[0] - q0[0], q2[1] - q0[1], q2[2] - q0[2]};
    double x = nr[0] * (u[1] * w[2] - u[2] * w[1]) + nr[1] * (u[2] * w[0] - u[0] * w[2]) + nr[2] * (u[0] * w[1] - u[1] * w[0]);
    { /* the face's own orientation against A's outward normals (not its winding: see the signature) */
      const double *p0 = mA->V + 3 * (size_t)t[0], *p1 = mA->V + 3 * (size_t)t[1], *p2 = mA->V + 3 * (size_t)t[2];
      const double *n0 = A->normals + 3 * (size_t)t[0], *n1 = A->normals + 3 * (size_t)t[1], *n2 = A->normals + 3 * (size_t)t[2];
      double a[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, b[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
      double y = (n0[0] + n1[0] + n2[0]) * (a[1] * b[2] - a[2] * b[1]) + (n0[1] + n1[1] + n2[1]) * (a[2] * b[0] - a[0] * b[2]) +
                 (n0[2] + n1[2] + n2[2]) * (a[0] * b[1] - a[1] * b[0]);
      if (y < 0) x = -x;
      else if (!(y > 0)) continue;
    }
    if (x == 0) continue;
    tot += 1, pos += x > 0;
    if (seg) cnt[lab[t[0]]] += 1, cpos[lab[t[0]]] += x > 0;
  }
  if (seg)
    for (int a = 0; a < m; a++) seg[a] = cnt[a] > 0 ? (2 * cpos[a] - cnt[a]) / cnt[a] : NAN;
  return tot > 0 ? (2 * pos - tot) / tot : 0.0;
}

double ssi_map_orientation(const ss_centre_signature *A, const ss_centre_signature *B, const int *T) {
  return map_orientation_seg(A, B, T, NULL, NULL);
}

double ssi_map_orientation_reversed(const ss_centre_signature *A, const ss_centre_signature *B, const int *T, double thr,
                                    double *seg, double *smin) {
  (void)map_orientation_seg(A, B, T, NULL, seg);
  double mn = INFINITY;
  int scored = 0, below = 0;
  for (int a = 0; a < A->m; a++)
    if (isfinite(seg[a])) {
      scored++, below += seg[a] < thr;
      if (seg[a] < mn) mn = seg[a];
    }
  if (smin) *smin = isfinite(mn) ? mn : 0.0;
  return scored ? (double)below / scored : 1.0;
}

/* The median over A's segments of s1 − s2 (segments scored in both), 0 when none */
double ssi_median_margin(int m, const double *s1, const double *s2, double *tmp) {
  int q = 0;
  for (int a = 0; a < m; a++)
    if (isfinite(s1[a]) && isfinite(s2[a])) {
      double d = s1[a] - s2[a];
      int j = q++;
      for (; j > 0 && tmp[j - 1] > d; j--) tmp[j] = tmp[j - 1];
      tmp[j] = d;
    }
  if (q == 0) return 0.0;
  return q % 2 ? tmp[q / 2] : 0.5 * (tmp[q / 2 - 1] + tmp[q / 2]);
}

/* The orientation test of a pairing p (A index -> B index): score of the map A -> B of a small
 * functional map (k eigenfunctions, descriptors from descr_k eigenpairs, ZoomOut up to zk when
 * zk > k, on ns samples of A) with the paired centres as landmarks. */
static ss_status orient_score_T(const ss_centre_signature *A, const ss_centre_signature *B, const int *p, int k,
                                int descr_k, int zk, int ns, double keep, double *score, int *Tout, ss_error *err) {
  const ss_shape_prep *pA = A->prep, *pB = B->prep;
  const int m = A->m, kmin = pA->kev < pB->kev ? pA->kev : pB->kev;
  ss_fmap_match_options fo;
  ss_fmap_match_default_options(&fo);
  fo.k = k < kmin ? k : kmin;
  fo.descr_k = descr_k < kmin ? descr_k : kmin;
  if (fo.descr_k < fo.k) fo.descr_k = fo.k;
  fo.zoomout_kmax = 0;
  if (zk > fo.k) {
    fo.zoomout_kmax = zk < kmin ? zk : kmin;
    fo.zoomout_step = 5;
    fo.zoomout_samples = ns > 0 && ns < pA->mesh->nv ? ns : 0;
    if (fo.zoomout_kmax <= fo.k) fo.zoomout_kmax = 0;
  }
  int *lA = malloc(sizeof(int) * (size_t)m), *lB = malloc(sizeof(int) * (size_t)m);
  int *T = malloc(sizeof(int) * (size_t)pA->mesh->nv), *ord = malloc(sizeof(int) * (size_t)m);
  double *ecc = malloc(sizeof(double) * (size_t)m);
  ss_status st = SS_OK;
  int na = m;
  if (!lA || !lB || !T || !ord || !ecc) st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
  if (!st) {
    /* keep < 1: only the round(keep · m) (at least 3) centres of A farthest on average from the
     * others (the protrusions: head, hands, feet on a body), in A's order */
    if (keep > 0 && keep < 1 && m > 3) {
      na = (int)floor(keep * m + 0.5);
      if (na < 3) na = 3;
      if (na > m) na = m;
    }
    for (int a = 0; a < m; a++) {
      ecc[a] = 0;
      for (int c = 0; c < m; c++) ecc[a] += A->D[a + (size_t)m * c];
      ord[a] = a;
    }
    for (int i = 1; i < m; i++) /* insertion sort by eccentricity, descending (ties: lower index) */
      for (int j = i; j > 0 && ecc[ord[j]] > ecc[ord[j - 1]]; j--) {
        int t = ord[j];
        ord[j] = ord[j - 1], ord[j - 1] = t;
      }
    int q = 0;
    for (int a = 0; a < m; a++) {
      int kept = 0;
      for (int i = 0; i < na; i++) kept |= ord[i] == a;
      if (kept) lA[q] = A->centers[a], lB[q++] = B->centers[p[a]];
    }
    ss_fmap_shape sA = {pA->mesh, pA->M, pA->evals, pA->evecs, pA->kev, NULL, 0, NULL, 0},
                  sB = {pB->mesh, pB->M, pB->evals, pB->evecs, pB->kev, NULL, 0, NULL, 0};
    st = ss_fmap_match(&sA, &sB, na, lA, lB, 0, NULL, NULL, SS_PROBE_RAW, &fo, T, NULL, err);
  }
  if (!st && score) *score = ssi_map_orientation(A, B, T);
  if (!st && Tout) memcpy(Tout, T, sizeof(int) * (size_t)pA->mesh->nv);
  free(lA), free(lB), free(T), free(ord), free(ecc);
  return st;
}

static ss_status orient_score(const ss_centre_signature *A, const ss_centre_signature *B, const int *p, int k, int descr_k,
                              int zk, int ns, double keep, double *score, ss_error *err) {
  return orient_score_T(A, B, p, k, descr_k, zk, ns, keep, score, NULL, err);
}

/* kept[a] = 1 for the round(keep · m) (at least 3) centres farthest on average from the others */
void ssi_kept_centres(const ss_centre_signature *A, double keep, int *kept) {
  const int m = A->m;
  int na = m;
  if (keep > 0 && keep < 1 && m > 3) {
    na = (int)floor(keep * m + 0.5);
    if (na < 3) na = 3;
    if (na > m) na = m;
  }
  for (int a = 0; a < m; a++) {
    double ea = 0;
    for (int c = 0; c < m; c++) ea += A->D[a + (size_t)m * c];
    int rank = 0;
    for (int b = 0; b < m; b++) {
      double eb = 0;
      for (int c = 0; c < m; c++) eb += A->D[b + (size_t)m * c];
      rank += eb > ea || (eb == ea && b < a);
    }
    kept[a] = rank < na;
  }
}

void ssi_orient_ctx_free(ssi_orient_ctx *c) {
  ss_fmap_probes_free(&c->pA), ss_fmap_probes_free(&c->pB);
  free(c->kept), free(c->Abuf), free(c->Pbuf), free(c->T);
  memset(c, 0, sizeof *c);
}

/* the orientation test's functional-map options for shapes with kmin eigenpairs */
void ssi_orient_fmap_options(int k, int descr_k, int kmin, ss_fmap_match_options *fo) {
  ss_fmap_match_default_options(fo);
  fo->k = k < kmin ? k : kmin;
  fo->descr_k = descr_k < kmin ? descr_k : kmin;
  if (fo->descr_k < fo->k) fo->descr_k = fo->k;
  fo->zoomout_kmax = 0;
}

/* the signature's own probes when they were built with these options and at least this basis: the
 * probe functions do not depend on the basis (they are synthesised from descr_k eigenpairs), so the
 * coefficients in the first k eigenfunctions are the first k rows, and the packed operators of the
 * first k the first k(k+1)/2 entries of each column */
static int have_probes(const ss_centre_signature *s, const ss_fmap_match_options *fo, int per) {
  return s->probe_A && s->probe_P && s->probe_k >= fo->k && s->probe_descr_k == fo->descr_k && s->probe_p == per * (1 + s->m);
}

/* columns [c0, c0 + nc) of probes with basis ks (coefficients A, packed operators P) into the basis
 * k <= ks (dA, dP: nc columns) */
static void copy_probe_columns(int ks, const double *A, const double *P, int c0, int nc, int k, double *dA, double *dP) {
  const size_t kps = (size_t)ks * (ks + 1) / 2, kp = (size_t)k * (k + 1) / 2;
  for (int j = 0; j < nc; j++) {
    memcpy(dA + (size_t)k * j, A + (size_t)ks * (c0 + j), sizeof(double) * (size_t)k);
    memcpy(dP + kp * j, P + kps * (c0 + j), sizeof(double) * kp);
  }
}

ss_status ssi_orient_ctx_new(const ss_centre_signature *A, const ss_centre_signature *B, int k, int descr_k, double keep,
                             ssi_orient_ctx *c, ss_error *err) {
  memset(c, 0, sizeof *c);
  const ss_shape_prep *pA = A->prep, *pB = B->prep;
  const int m = A->m, kmin = pA->kev < pB->kev ? pA->kev : pB->kev;
  c->A = A, c->B = B;
  ssi_orient_fmap_options(k, descr_k, kmin, &c->fo);
  if (c->fo.n_energies % c->fo.descr_step) return ss_fail(err, SS_ERR_INVALID, "autopair: descr_step must divide n_energies");
  c->per = c->fo.n_energies / c->fo.descr_step;
  c->sA = (ss_fmap_shape){pA->mesh, pA->M, pA->evals, pA->evecs, pA->kev, NULL, 0, NULL, 0};
  c->sB = (ss_fmap_shape){pB->mesh, pB->M, pB->evals, pB->evecs, pB->kev, NULL, 0, NULL, 0};
  const int kk = c->fo.k, kp = kk * (kk + 1) / 2, per = c->per;
  int *mask = malloc(sizeof(int) * (size_t)m), *lA = malloc(sizeof(int) * (size_t)m);
  c->kept = malloc(sizeof(int) * (size_t)m);
  c->T = malloc(sizeof(int) * (size_t)pA->mesh->nv);
  ss_status st = SS_OK;
  if (!mask || !lA || !c->kept || !c->T) st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
  if (!st) {
    ssi_kept_centres(A, keep, mask);
    for (int a = 0; a < m; a++)
      if (mask[a]) lA[c->na] = A->centers[a], c->kept[c->na++] = a;
    c->nb = B->m;
    const int p = per * (1 + c->na);
    c->Abuf = malloc(sizeof(double) * (size_t)kk * p);
    c->Pbuf = malloc(sizeof(double) * (size_t)kp * p);
    if (!c->Abuf || !c->Pbuf) st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
  }
  /* B: its signature's probes, or built here */
  if (!st && have_probes(B, &c->fo, per)) c->bA = B->probe_A, c->bP = B->probe_P, c->bk = B->probe_k;
  else if (!st && !(st = ss_fmap_base_probes(&c->sB, B->m, B->centers, &c->fo, 1, &c->pB, err)))
    c->bA = c->pB.A, c->bP = c->pB.P, c->bk = kk;
  /* A: the WKS and its kept centres, in A's order, from its signature's probes or built here */
  if (!st && have_probes(A, &c->fo, per)) {
    c->pA = (ss_fmap_probes){kk, per * (1 + c->na), per * (1 + c->na), NULL, NULL, 0, NULL};
    c->pA.A = malloc(sizeof(double) * (size_t)kk * c->pA.p);
    c->pA.P = malloc(sizeof(double) * (size_t)kp * c->pA.p);
    if (!c->pA.A || !c->pA.P) st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
    for (int i = 0; !st && i <= c->na; i++) {
      const int src = i == 0 ? 0 : 1 + c->kept[i - 1];
      copy_probe_columns(A->probe_k, A->probe_A, A->probe_P, per * src, per, kk, c->pA.A + (size_t)kk * per * i,
                         c->pA.P + (size_t)kp * per * i);
    }
  } else if (!st) {
    st = ss_fmap_base_probes(&c->sA, c->na, lA, &c->fo, 1, &c->pA, err);
  }
  if (!st) st = ss_fmap_pair_weights(&c->sA, &c->sB, &c->fo, &c->w, err);
  if (!st && (c->pA.p != per * (1 + c->na) || (c->pB.A && c->pB.p != per * (1 + B->m))))
    st = ss_fail(err, SS_ERR_INVALID, "autopair: unexpected probe layout");
  free(mask), free(lA);
  if (st) ssi_orient_ctx_free(c);
  return st;
}

/* the point map A -> B of candidate p (A index -> B index) into c->T, and its orientation score */
ss_status ssi_orient_ctx_score(ssi_orient_ctx *c, const int *p, double *score, double *seg, ss_error *err) {
  const int kk = c->fo.k, kp = kk * (kk + 1) / 2, per = c->per, np = per * (1 + c->na);
  for (int i = 0; i <= c->na; i++) { /* item 0: the WKS; item i: centre p[kept[i-1]] of B */
    const int src = i == 0 ? 0 : 1 + p[c->kept[i - 1]];
    copy_probe_columns(c->bk, c->bA, c->bP, per * src, per, kk, c->Abuf + (size_t)kk * per * i, c->Pbuf + (size_t)kp * per * i);
  }
  ss_fmap_probes pb = {kk, np, np, c->Abuf, c->Pbuf, 0, NULL};
  ss_fmap_system *sys = NULL;
  double *Ck = malloc(sizeof(double) * (size_t)kk * kk);
  ss_status st = Ck ? SS_OK : ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
  /* source B, target A: C maps functions on B to functions on A, its point map is A -> B */
  if (!st) st = ss_fmap_system_new(kk, kk, c->sB.evals, c->sA.evals, &pb, &c->pA, &c->w, &sys, err);
  if (!st) st = ss_fmap_system_solve(sys, NULL, NULL, 0.0, 0, Ck, err);
  if (!st) st = ss_fmap_match_finish(&c->sA, &c->sB, &c->fo, Ck, c->T, NULL, err);
  if (!st && score) *score = map_orientation_seg(c->A, c->B, c->T, NULL, seg);
  ss_fmap_system_free(sys);
  free(Ck);
  return st;
}

ss_status ssi_orient_pair(const ss_centre_signature *A, const ss_centre_signature *B, const int *p1, const int *p2, int k,
                          int descr_k, double keep, double *r1, double *r2, double *med, ss_error *err) {
  ssi_orient_ctx c;
  ss_status st = ssi_orient_ctx_new(A, B, k, descr_k, keep, &c, err);
  double *s1 = malloc(sizeof(double) * 2 * (size_t)A->m), *s2 = malloc(sizeof(double) * 2 * (size_t)A->m);
  double *tmp = malloc(sizeof(double) * (size_t)A->m);
  if (!st && (!s1 || !s2 || !tmp)) st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
  if (!st) st = ssi_orient_ctx_score(&c, p1, r1, s1, err);
  if (!st) st = ssi_orient_ctx_score(&c, p2, r2, s2, err);
  if (!st && med) *med = ssi_median_margin(A->m, s1, s2, tmp);
  free(s1), free(s2), free(tmp);
  ssi_orient_ctx_free(&c);
  return st;
}

ss_status ssi_autopair_orient_score(const ss_centre_signature *A, const ss_centre_signature *B, const int *p,
                                    const ss_autopair_options *o, double *score, ss_error *err) {
  return orient_score(A, B, p, o->orient_k, o->orient_descr_k, 0, 0, 1.0, score, err);
}

ss_status ssi_autopair_recheck_score(const ss_centre_signature *A, const ss_centre_signature *B, const int *p,
                                     const ss_autopair_options *o, double *score, ss_error *err) {
  return orient_score(A, B, p, o->recheck_k, o->orient_descr_k, o->recheck_zoomout, o->recheck_samples, o->orient_keep,
                      score, err);
}
