/* A shape's centre signature (match.h), what the landmark-free pairing compares: the exact geodesics
 * from its segment centres (their distances), the WKS averaged around each centre, outward vertex
 * normals, the orientation tests' probes, and the centres' own left-right symmetry σ. */
#include "specseg/fmap.h"
#include "specseg/geodesic.h"
#include "specseg/match.h"
#include "match/autopair_internal.h"
#include "mesh/mesh_topology.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ss_centre_signature_free(ss_centre_signature *s) {
  if (!s) return;
  free(s->centers);
  free(s->descr);
  free(s->D);
  free(s->normals);
  free(s->sigma);
  free(s->probe_A);
  free(s->probe_P);
  memset(s, 0, sizeof *s);
}

static ss_status self_symmetry(ss_centre_signature *sg, const ss_autopair_options *o, ss_error *err);

ss_status ss_centre_signature_compute(const ss_shape_prep *p, const ss_autopair_options *o_in, ss_centre_signature *out,
                                      ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "autopair: NULL output");
  memset(out, 0, sizeof *out);
  ss_autopair_options o;
  if (o_in) o = *o_in;
  else ss_autopair_default_options(&o);
  if (!p || !p->mesh || !p->evecs || !p->evals || !p->M || !p->seg.centers || p->seg.m < 1)
    return ss_fail(err, SS_ERR_INVALID, "autopair: shape not prepared");
  if (o.n_energies < 1 || !(o.sigma_factor > 0) || !(o.descr_radius >= 0) || o.descr_k < 3 || o.orient_k < 3 ||
      o.orient_descr_k < 3)
    return ss_fail(err, SS_ERR_INVALID, "autopair: bad descriptor options");
  const ss_mesh *mesh = p->mesh;
  const int n = mesh->nv, nf = mesh->nf, m = p->seg.m, ne = o.n_energies;
  const int kw = o.descr_k < p->kev ? o.descr_k : p->kev;
  for (int a = 0; a < m; a++)
    if (p->seg.centers[a] < 0 || p->seg.centers[a] >= n)
      return ss_fail(err, SS_ERR_INVALID, "autopair: centre %d out of range", a);
  ss_status st = SS_OK;
  ss_geodesic_mesh *gm = NULL;
  double *F = malloc(sizeof(double) * (size_t)n * m), *W = malloc(sizeof(double) * (size_t)n * ne);
  out->m = m;
  out->nd = ne;
  out->prep = p;
  out->centers = malloc(sizeof(int) * (size_t)m);
  out->descr = malloc(sizeof(double) * (size_t)m * ne);
  out->D = malloc(sizeof(double) * (size_t)m * m);
  out->normals = calloc((size_t)n * 3, sizeof(double));
  out->sigma = malloc(sizeof(int) * (size_t)m);
  if (!F || !W || !out->centers || !out->descr || !out->D || !out->normals || !out->sigma) {
    st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
    goto done;
  }
  memcpy(out->centers, p->seg.centers, sizeof(int) * (size_t)m);
  const double area = ss_mesh_area(mesh), scale = 1.0 / sqrt(area);
  /* 1. exact fields from the centres, scaled */
  if ((st = ss_geodesic_mesh_build(mesh, &gm, err))) goto done;
  if ((st = ss_geodesic_fields(gm, out->centers, m, 0.0, F, err))) goto done;
  for (size_t i = 0; i < (size_t)n * m; i++) {
    if (!isfinite(F[i])) {
      st = ss_fail(err, SS_ERR_INVALID, "autopair: a segment centre does not reach every vertex (several components)");
      goto done;
    }
    F[i] *= scale;
  }
  for (int a = 0; a < m; a++)
    for (int b = 0; b < m; b++)
      out->D[a + (size_t)m * b] = 0.5 * (F[out->centers[b] + (size_t)n * a] + F[out->centers[a] + (size_t)n * b]);
  /* 2. WKS averaged over a disc around each centre, unit length */
  if ((st = ss_wks(n, kw, p->evals, p->evecs, p->M, ne, o.sigma_factor, W, err))) goto done;
  for (int a = 0; a < m; a++) {
    double *d = out->descr + (size_t)a * ne, wsum = 0;
    memset(d, 0, sizeof(double) * (size_t)ne);
    if (o.descr_radius > 0) {
      for (int v = 0; v < n; v++)
        if (F[v + (size_t)n * a] <= o.descr_radius) {
          wsum += p->M[v];
          for (int j = 0; j < ne; j++) d[j] += p->M[v] * W[v + (size_t)n * j];
        }
    }
    if (!(wsum > 0))
      for (int j = 0; j < ne; j++) d[j] = W[out->centers[a] + (size_t)n * j];
    double nn = 0;
    for (int j = 0; j < ne; j++) nn += d[j] * d[j];
    nn = nn > 0 ? 1.0 / sqrt(nn) : 0.0;
    for (int j = 0; j < ne; j++) d[j] *= nn;
  }
  /* 3. orientation: the signed volume's sign makes the normals outward; faces of a mesh that is not
   * consistently oriented are taken as the consistent orientation of their component (majority)
   * would have them, so the normals do not depend on the faces' own winding */
  {
    int *Fo = NULL;
    if ((st = ssi_mesh_orient_copy(mesh, &Fo, NULL, err))) goto done;
    const int *FF = Fo ? Fo : mesh->F;
    const double vol = ssi_mesh_signed_volume6(mesh, FF) / 6.0;
    for (int f = 0; f < nf; f++) {
      const int *t = FF + 3 * (size_t)f;
      const double *p0 = mesh->V + 3 * (size_t)t[0], *p1 = mesh->V + 3 * (size_t)t[1], *p2 = mesh->V + 3 * (size_t)t[2];
      double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, w[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
      double N[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      for (int c = 0; c < 3; c++)
        for (int d = 0; d < 3; d++) out->normals[3 * (size_t)t[c] + d] += N[d];
    }
    free(Fo);
    out->volume_ratio = vol / (area * sqrt(area));
    out->orient_sign = vol < 0 ? -1.0 : 1.0;
    for (size_t i = 0; i < (size_t)n * 3; i++) out->normals[i] *= out->orient_sign;
  }
  /* 4. the orientation tests' probes (WKS + every centre's wave kernels), once per shape, in the
   * larger of the two tests' bases (the other takes its leading block) */
  {
    ss_fmap_match_options fo;
    const int kt = o.recheck_margin > 0 && o.recheck_zoomout <= o.recheck_k && o.recheck_k > o.orient_k ? o.recheck_k : o.orient_k;
    ssi_orient_fmap_options(kt, o.orient_descr_k, p->kev, &fo);
    ss_fmap_shape fs = {mesh, p->M, p->evals, p->evecs, p->kev, NULL, 0, NULL, 0};
    ss_fmap_probes pr;
    if ((st = ss_fmap_base_probes(&fs, m, out->centers, &fo, 1, &pr, err))) goto done;
    out->probe_k = fo.k, out->probe_descr_k = fo.descr_k, out->probe_p = pr.p, out->probe_A = pr.A, out->probe_P = pr.P;
  }
  /* 5. the centres' own left-right symmetry */
  st = self_symmetry(out, &o, err);
done:
  ss_geodesic_mesh_free(gm);
  free(F), free(W);
  if (st) ss_centre_signature_free(out);
  return st;
}

#define SELF_CANDIDATES 6

/* σ: of the SELF_CANDIDATES best non-identity pairings of the centres with themselves (intrinsic
 * energy), the one whose map is the most clearly orientation-reversing (a mirror); identity when
 * none reverses (score ≥ 0). */
static ss_status self_symmetry(ss_centre_signature *sg, const ss_autopair_options *o, ss_error *err) {
  const int m = sg->m;
  for (int a = 0; a < m; a++) sg->sigma[a] = a;
  sg->sigma_score = 1.0;
  if (m < 2) return SS_OK;
  double *U = malloc(sizeof(double) * (size_t)m * m), *minU = malloc(sizeof(double) * ((size_t)m + 1));
  int *cur = malloc(sizeof(int) * (size_t)m), *used = malloc(sizeof(int) * (size_t)m);
  int *buf = malloc(sizeof(int) * (size_t)m * SSI_TOPK);
  ss_status st = SS_OK;
  int status = 0, moved[SSI_TOPK];
  double sc_k[SSI_TOPK], best_sc = INFINITY;
  if (!U || !minU || !cur || !used || !buf) st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
  ssi_search S;
  S.ntop = 0;
  if (!st) {
    ssi_init_search(&S, sg, o, U, minU, cur, used, buf);
    ssi_fill_unary(&S, U, minU, sg, sg, o->w_descr);
    const int exact = m <= o->exact_max && ssi_count_injections(m, m) <= 5e7;
    ssi_run_search(&S, exact, SELF_CANDIDATES + 1 < SSI_TOPK ? SELF_CANDIDATES + 1 : SSI_TOPK, 1, &status);
    if (status) st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
  }
  ssi_orient_ctx oc = {0};
  int have_ctx = 0;
  for (int k = 0; !st && k < S.ntop; k++) {
    if (!isfinite(S.top_e[k])) break;
    int id = 1;
    for (int a = 0; a < m && id; a++) id = S.top_p[k][a] == a;
    if (id) continue;
    double sc = 0;
    if (!have_ctx && (st = ssi_orient_ctx_new(sg, sg, o->orient_k, o->orient_descr_k, 1.0, &oc, err))) break;
    have_ctx = 1;
    if ((st = ssi_orient_ctx_score(&oc, S.top_p[k], &sc, NULL, err))) break;
    sc_k[k] = sc;
    moved[k] = 0;
    for (int a = 0; a < m; a++) moved[k] += S.top_p[k][a] != a;
    if (sc < best_sc) best_sc = sc;
  }
  /* a partial swap (e.g. the hands only) reverses orientation too: of the candidates that reverse
   * it clearly (score ≤ half the most negative one), the one moving the most centres, then the
   * lowest score */
  int pick = -1;
  for (int k = 0; !st && k < S.ntop && best_sc < 0; k++) {
    if (!isfinite(S.top_e[k]) || moved[k] == 0 || !(sc_k[k] <= 0.5 * best_sc)) continue;
    if (pick < 0 || moved[k] > moved[pick] || (moved[k] == moved[pick] && sc_k[k] < sc_k[pick])) pick = k;
  }
  if (pick >= 0) sg->sigma_score = sc_k[pick], memcpy(sg->sigma, S.top_p[pick], sizeof(int) * (size_t)m);
  ssi_orient_ctx_free(&oc);
  free(U), free(minU), free(cur), free(used), free(buf);
  return st;
}
