/* The matching pipeline of paper §6 on two meshes: per-shape preparation (segmentation and
 * eigenpairs), pairing of the segments, segment indicators as extra probes, functional map, ZoomOut. */
#include "specseg/match.h"
#include "specseg/geodesic.h"
#include "specseg/laplacian.h"
#include "specseg/mesh.h"
#include "specseg/spectrum.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ss_shape_prep_free(ss_shape_prep *p) {
  if (!p) return;
  ss_segmentation_free(&p->seg);
  free(p->evals);
  free(p->evecs);
  free(p->M);
  memset(p, 0, sizeof *p);
}

/* 1 when ss_mesh_sanitize would return the mesh as it is (then input vertex = processed vertex, which
 * is what Ψ and the landmark indices assume). */
static ss_status check_clean(const ss_mesh *m, ss_error *err) {
  ss_mesh clean = {0};
  int *to_input = NULL;
  ss_status st = ss_mesh_sanitize(m, &clean, &to_input, NULL, 0, err);
  if (st) return st;
  int same = clean.nv == m->nv && clean.nf == m->nf;
  for (int i = 0; same && i < clean.nv; i++) same = to_input[i] == i;
  ss_mesh_free(&clean);
  free(to_input);
  if (!same)
    return ss_fail(err, SS_ERR_INVALID,
                   "match: the mesh has degenerate/duplicate faces, unreferenced or non-manifold vertices; "
                   "repair it first (its vertex indices are what landmarks and maps refer to)");
  return SS_OK;
}

ss_status ss_shape_prep_compute(const ss_mesh *m, const ss_segment_options *seg_opts, int kev, ss_shape_prep *out,
                                ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  if (!m || m->nv < 4 || m->nf < 1 || !m->V || !m->F) return ss_fail(err, SS_ERR_INVALID, "match: empty mesh");
  if (kev < 3 || kev >= m->nv)
    return ss_fail(err, SS_ERR_INVALID, "match: %d eigenpairs requested on %d vertices", kev, m->nv);
  ss_status st = check_clean(m, err);
  if (st) return st;
  out->mesh = m;
  double t0 = ss_time();
  if ((st = ss_segment(m, seg_opts, &out->seg, err))) goto fail;
  double t1 = ss_time();
  out->kev = kev;
  out->evals = malloc(sizeof(double) * (size_t)kev);
  out->evecs = malloc(sizeof(double) * (size_t)m->nv * kev);
  out->M = malloc(sizeof(double) * (size_t)m->nv);
  if (!out->evals || !out->evecs || !out->M) {
    st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory for %d eigenpairs", kev);
    goto fail;
  }
  if ((st = ss_mesh_eigs(m, kev, out->evals, out->evecs, err))) goto fail;
  if ((st = ss_mass_lumped(m, SS_MASS_BARYCENTRIC, out->M, err))) goto fail;
  out->area = 0;
  for (int i = 0; i < m->nv; i++) out->area += out->M[i];
  out->t_segment = t1 - t0;
  out->t_eigs = ss_time() - t1;
  return SS_OK;
fail:
  ss_shape_prep_free(out);
  return st;
}

void ss_match_default_options(ss_match_options *o) {
  memset(o, 0, sizeof *o);
  o->probes = SS_PROBES_DIFF;
  ss_fmap_match_default_options(&o->fmap);
  ss_segment_default_options(&o->seg);
  o->segment_profile = 1;
}

void ss_match_result_free(ss_match_result *r) {
  if (!r) return;
  free(r->map);
  free(r->C);
  free(r->centerX);
  free(r->centerY);
  ss_segment_pairs_free(&r->pairs);
  memset(r, 0, sizeof *r);
}

/* Indicator functions of the paired segments: E (n x npairs), column p = 1 on segment seg[p]. */
static double *indicators(int n, const int *labels, int npairs, const int *seg) {
  double *E = calloc((size_t)n * (npairs > 0 ? npairs : 1), sizeof(double));
  if (!E) return NULL;
  int m = 0;
  for (int p = 0; p < npairs; p++) m = seg[p] + 1 > m ? seg[p] + 1 : m;
  int *col = malloc(sizeof(int) * (size_t)(m > 0 ? m : 1)); /* segment → column, -1 when unpaired */
  if (!col) {
    free(E);
    return NULL;
  }
  for (int s = 0; s < m; s++) col[s] = -1;
  for (int p = 0; p < npairs; p++) col[seg[p]] = p;
  for (int i = 0; i < n; i++) {
    int s = labels[i];
    if (s >= 0 && s < m && col[s] >= 0) E[i + (size_t)n * col[s]] = 1.0;
  }
  free(col);
  return E;
}

/* The tent profile (ss_match_options.segment_profile = 1): each nonzero column of E becomes
 * 1 − d/R on its segment, d the segmentation's distance (work mesh, through Ψ) to the centre. */
static void tent_profile(const ss_segmentation *sg, int n, int npairs, double *E) {
  for (int p = 0; p < npairs; p++) {
    double *f = E + (size_t)n * p, R = 0;
    for (int i = 0; i < n; i++)
      if (f[i] > 0 && sg->psi[i] >= 0 && sg->work_dist[sg->psi[i]] > R) R = sg->work_dist[sg->psi[i]];
    if (!(R > 0)) continue;
    for (int i = 0; i < n; i++)
      if (f[i] > 0) f[i] = sg->psi[i] >= 0 ? 1.0 - sg->work_dist[sg->psi[i]] / R : 0.0;
  }
}

/* Temperature of the soft iVd profile, in units of sqrt(area) of the work mesh. FAUST (BEST, tune
 * seed 7 / held out seed 11): 0.1 and 0.2 equal, 0.3 and 0.5 lose most of the gain (see match.h). */
#define SOFT_IVD_TAU 0.2

/* The soft iVd profile (segment_profile = 2): column p = exp(−d_s/τ) / Σ_j exp(−d_j/τ), s = seg[p],
 * d_j the NPP22-graph distance on the work mesh from the centre of segment j (the distances whose
 * arg-min is the iVd, i.e. the segments themselves as τ → 0), pulled back through Ψ. The columns of
 * all m segments would sum to 1: a partition of unity whose transitions are τ wide instead of a step
 * at a boundary that the other shape places elsewhere. */
static ss_status soft_ivd_profile(const ss_segmentation *sg, int npairs, const int *seg, double *E, ss_error *err) {
  const int n = sg->nv, nw = sg->work.nv, m = sg->m;
  ss_graph g = {0};
  double *D = malloc(sizeof(double) * (size_t)nw * (m > 0 ? m : 1));
  ss_status st = SS_OK;
  if (!D) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory for segment probes"); goto done; }
  if ((st = ss_graph_npp22(&sg->work, &g, err))) goto done;
  for (int j = 0; j < m; j++)
    if ((st = ss_graph_dijkstra(&g, sg->crit + j, 1, 0, D + (size_t)nw * j, NULL, err))) goto done;
  const double area = ss_mesh_area(&sg->work), tau = SOFT_IVD_TAU * sqrt(area > 0 ? area : 1.0);
  for (int x = 0; x < n; x++) {
    int w = sg->psi[x];
    double dmin = INFINITY, z = 0;
    if (w >= 0 && w < nw)
      for (int j = 0; j < m; j++) dmin = fmin(dmin, D[w + (size_t)nw * j]);
    if (!isfinite(dmin)) { /* no centre reaches it (or no work vertex): in no segment */
      for (int p = 0; p < npairs; p++) E[x + (size_t)n * p] = 0;
      continue;
    }
    for (int j = 0; j < m; j++) z += exp(-(D[w + (size_t)nw * j] - dmin) / tau);
    for (int p = 0; p < npairs; p++) E[x + (size_t)n * p] = exp(-(D[w + (size_t)nw * seg[p]] - dmin) / tau) / z;
  }
done:
  ss_graph_free(&g);
  free(D);
  return st;
}

ss_status ss_segment_probes(const ss_segmentation *sg, int npairs, const int *seg, int profile, double **E,
                            ss_error *err) {
  *E = NULL;
  if (profile < 0 || profile > 2) return ss_fail(err, SS_ERR_INVALID, "match: unknown segment profile %d", profile);
  for (int p = 0; p < npairs; p++)
    if (seg[p] < 0 || seg[p] >= sg->m)
      return ss_fail(err, SS_ERR_INVALID, "match: paired segment %d out of range [0,%d)", seg[p], sg->m);
  if (profile == 1 && (!sg->work_dist || !sg->psi))
    return ss_fail(err, SS_ERR_INVALID, "match: the tent segment profile needs the segmentation's distances");
  if (profile == 2 && (!sg->psi || !sg->crit || sg->work.nv < 1 || !sg->work.V || !sg->work.F))
    return ss_fail(err, SS_ERR_INVALID, "match: the soft segment profile needs the segmentation's work mesh");
  *E = indicators(sg->nv, sg->labels, npairs, seg);
  if (!*E) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory for segment probes");
  if (profile == 1) tent_profile(sg, sg->nv, npairs, *E);
  if (profile == 2) {
    ss_status st = soft_ivd_profile(sg, npairs, seg, *E, err);
    if (st) {
      free(*E);
      *E = NULL;
      return st;
    }
  }
  return SS_OK;
}

ss_status ss_match_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                            const ss_match_options *opts_in, ss_match_result *out, ss_error *err) {
  double t_start = ss_time();
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y || !X->mesh || !Y->mesh || !X->evecs || !Y->evecs)
    return ss_fail(err, SS_ERR_INVALID, "match: shapes not prepared");
  if (o.segment_profile < 0 || o.segment_profile > 2)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown segment profile %d", o.segment_profile);
  if (o.probes < SS_PROBES_STD || o.probes > SS_PROBES_DIFF)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown probe set %d", (int)o.probes);
  if (nl < 1 || !lmX || !lmY) return ss_fail(err, SS_ERR_INVALID, "match: needs at least one landmark");
  const int nX = X->mesh->nv, nY = Y->mesh->nv, k = o.fmap.k, kz = o.fmap.zoomout_kmax;
  for (int i = 0; i < nl; i++) {
    if (lmX[i] < 0 || lmX[i] >= nX)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on X [0,%d)", i, lmX[i], nX);
    if (lmY[i] < 0 || lmY[i] >= nY)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on Y [0,%d)", i, lmY[i], nY);
  }
  if (k < 3 || (kz != 0 && kz < k))
    return ss_fail(err, SS_ERR_INVALID, "match: bad basis sizes (k %d, ZoomOut %d)", k, kz);
  int need = kz > k ? kz : k;
  if (X->kev < need || Y->kev < need)
    return ss_fail(err, SS_ERR_INVALID, "match: %d eigenpairs needed, shapes have %d and %d", need, X->kev, Y->kev);

  ss_status st = SS_OK;
  double *EX = NULL, *EY = NULL, *Ck = NULL;
  out->nX = nX;
  out->t_segment = X->t_segment + Y->t_segment;
  out->t_eigs = X->t_eigs + Y->t_eigs;

  /* 1. pairing of the segments (reported for every probe set) */
  double t0 = ss_time();
  if ((st = ss_pair_segments(&X->seg, &Y->seg, nl, lmX, lmY, &out->pairs, err))) goto fail;
  int np = out->pairs.n;
  out->centerX = malloc(sizeof(int) * (size_t)(np > 0 ? np : 1));
  out->centerY = malloc(sizeof(int) * (size_t)(np > 0 ? np : 1));
  if (!out->centerX || !out->centerY) goto nomem;
  for (int p = 0; p < np; p++) {
    out->centerX[p] = X->seg.centers[out->pairs.sx[p]];
    out->centerY[p] = Y->seg.centers[out->pairs.sy[p]];
  }
  double t1 = ss_time();
  out->t_pair = t1 - t0;

  /* 2. functional map at size k with the chosen probes */
  int nextra = o.probes == SS_PROBES_STD ? 0 : np;
  if (nextra > 0) {
    if ((st = ss_segment_probes(&X->seg, np, out->pairs.sx, o.segment_profile, &EX, err))) goto fail;
    if ((st = ss_segment_probes(&Y->seg, np, out->pairs.sy, o.segment_profile, &EY, err))) goto fail;
  }
  out->map = malloc(sizeof(int) * (size_t)nX);
  Ck = malloc(sizeof(double) * (size_t)k * k);
  if (!out->map || !Ck) goto nomem;
  ss_fmap_shape sX = {X->mesh, X->M, X->evals, X->evecs, X->kev}, sY = {Y->mesh, Y->M, Y->evals, Y->evecs, Y->kev};
  ss_fmap_match_options fo = o.fmap;
  fo.zoomout_kmax = 0; /* ZoomOut is run (and timed) below */
  if ((st = ss_fmap_match(&sX, &sY, nl, lmX, lmY, nextra, EX, EY,
                          o.probes == SS_PROBES_DIFF ? SS_PROBE_WAVE : SS_PROBE_RAW, &fo, out->map, Ck, err)))
    goto fail;
  double t2 = ss_time();
  out->t_fmap = t2 - t1;

  /* 3. optional ZoomOut from k to kz */
  if (kz > k) {
    out->kc = kz;
    out->C = malloc(sizeof(double) * (size_t)kz * kz);
    if (!out->C) goto nomem;
    int step = o.fmap.zoomout_step > 0 ? o.fmap.zoomout_step : 1;
    if ((st = ss_zoomout(nY, nX, Y->evecs, X->evecs, X->M, k, Ck, kz, step, out->map, out->C, err))) goto fail;
    out->t_zoomout = ss_time() - t2;
  } else {
    out->kc = k;
    out->C = Ck;
    Ck = NULL;
  }
  out->t_total = out->t_segment + out->t_eigs + (ss_time() - t_start);
  free(EX);
  free(EY);
  free(Ck);
  return SS_OK;
nomem:
  st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
fail:
  free(EX);
  free(EY);
  free(Ck);
  ss_match_result_free(out);
  return st;
}

ss_status ss_match(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                   const ss_match_options *opts_in, ss_match_result *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y) return ss_fail(err, SS_ERR_INVALID, "match: NULL mesh");
  /* check the landmarks before the expensive part */
  if (nl < 1 || !lmX || !lmY) return ss_fail(err, SS_ERR_INVALID, "match: needs at least one landmark");
  for (int i = 0; i < nl; i++) {
    if (lmX[i] < 0 || lmX[i] >= X->nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on X [0,%d)", i, lmX[i], X->nv);
    if (lmY[i] < 0 || lmY[i] >= Y->nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on Y [0,%d)", i, lmY[i], Y->nv);
  }
  int kev = o.fmap.zoomout_kmax > o.fmap.k ? o.fmap.zoomout_kmax : o.fmap.k;
  ss_shape_prep pX, pY;
  ss_status st = ss_shape_prep_compute(X, &o.seg, kev, &pX, err);
  if (st) return st;
  if ((st = ss_shape_prep_compute(Y, &o.seg, kev, &pY, err))) {
    ss_shape_prep_free(&pX);
    return st;
  }
  st = ss_match_prepared(&pX, &pY, nl, lmX, lmY, &o, out, err);
  ss_shape_prep_free(&pX);
  ss_shape_prep_free(&pY);
  return st;
}
