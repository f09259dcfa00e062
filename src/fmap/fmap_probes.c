/* The probe functions of one shape for Eq. (1), in its reduced basis: WKS descriptors, wave-kernel
 * maps of the landmarks (NO17), and extra paired functions (the segments) raw or wave-filtered.
 *
 * All filtered probes form one virtual column list [WKS | landmark 1 | … | landmark nl | extra 1 | …]
 * with n_energies columns per item, of which every descr_step-th column is kept (as pyFM does). The
 * base probes are the kept columns before the extras; the extra probes are the kept columns after
 * them — so building them apart gives exactly the columns of building them together, and a pair's
 * base probes can be computed once per shape and landmark set and shared by STD, ASA and DIFF. Only
 * the kept columns are synthesised (in the spectral domain, then one dgemm).
 *
 * The filtered probes are synthesised from the first kd = max(k, descr_k) eigenpairs (the WKS
 * filters on kd eigenvalues, the filtered functions' coefficients on kd eigenfunctions) and then
 * projected onto the first k, so a larger descr_k gives probes with more detail in the same basis.
 * kd = k is the NO17 / paper construction, computed by the same operations as before the option.
 *
 * The base probes are built as blocks [WKS | landmarks | own descriptors]. The WKS block depends on
 * the shape alone (a probe cache entry holds it). A landmark probe is Φ_kd c, so its operator is
 * Σ_l c_l T_l with the triple products T_l = Φ_kᵀ M diag(φ_l) Φ_k (also cached): one small dgemm
 * instead of a pass over the vertices per probe. */
#include "fmap/fmap_options.h"
#include "specseg/laplacian.h"
#include "mesh/mesh_topology.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Kept virtual columns c in [c_from, c_to) (c ≡ 0 mod step) as functions F (n x *nf, malloc'd), from
 * the first k eigenpairs (k here is the descriptor basis kd). Item 0 (columns 0..ne-1) is the WKS;
 * item i ≥ 1 is the wave filter of the function whose spectral coefficients are coef[:, i − item0]
 * (k rows; items below item0 must not be in the range). coef_out (may be NULL; then only filtered
 * columns in the range): their spectral coefficients, F = Φ_k *coef_out (k x *nf, malloc'd). */
static ss_status kept_columns(int n, int k, const double *evals, const double *evecs, const ss_fmap_match_options *o,
                              int item0, const double *coef, int c_from, int c_to, double **F, int *nf,
                              double **coef_out, ss_error *err) {
  const int ne = o->n_energies, step = o->descr_step;
  int first = (c_from + step - 1) / step * step, ncol = first < c_to ? (c_to - first + step - 1) / step : 0;
  int nwks = 0, nflt = 0;
  for (int c = first; c < c_to; c += step) {
    if (c < ne) nwks++;
    else nflt++;
  }
  double *G = malloc(sizeof(double) * (size_t)ne * k), *out = malloc(sizeof(double) * (size_t)n * (ncol > 0 ? ncol : 1));
  double *Gw = malloc(sizeof(double) * (size_t)(nwks > 0 ? nwks : 1) * k);
  double *fc = malloc(sizeof(double) * (size_t)k * (nflt > 0 ? nflt : 1)), *sq = NULL;
  ss_status st = SS_OK;
  if (!G || !out || !Gw || !fc) { st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); goto done; }
  if ((st = ss_wks_filters(evals, k, ne, o->sigma_factor, G, err))) goto done;
  int t = 0, f = 0;
  for (int c = first; c < c_to; c += step) {
    int item = c / ne, j = c % ne;
    if (item == 0)
      for (int i = 0; i < k; i++) Gw[t + (size_t)nwks * i] = G[j + (size_t)ne * i];
    else
      for (int i = 0; i < k; i++) fc[i + (size_t)k * f] = G[j + (size_t)ne * i] * coef[i + (size_t)k * (item - item0)];
    t += item == 0, f += item != 0;
  }
  if (nwks > 0) { /* WKS: Σ_i G[j,i] φ_i(x)² */
    if (!(sq = malloc(sizeof(double) * (size_t)n * k))) { st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); goto done; }
    for (size_t i = 0; i < (size_t)n * k; i++) sq[i] = evecs[i] * evecs[i];
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n, nwks, k, 1.0, sq, n, Gw, nwks, 0.0, out, n);
  }
  if (nflt > 0)
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, nflt, k, 1.0, evecs, n, fc, k, 0.0, out + (size_t)n * nwks, n);
  *F = out;
  *nf = ncol;
  out = NULL;
  if (coef_out) *coef_out = fc, fc = NULL;
done:
  free(G), free(out), free(Gw), free(fc), free(sq);
  return st;
}

/* F's columns each divided by its L²(M) norm (a zero column stays); norms (may be NULL): the norms
 * divided by (1 for a zero column) */
static void normalise_columns(int n, const double *M, int p, double *F, double *norms) {
  for (int c = 0; c < p; c++) {
    double *f = F + (size_t)n * c, s = 0;
    for (int x = 0; x < n; x++) s += M[x] * f[x] * f[x];
    if (norms) norms[c] = s > 0 ? sqrt(s) : 1.0;
    if (s > 0) cblas_dscal(n, 1.0 / sqrt(s), f, 1);
  }
}

/* Σ M, which the operators need positive and finite */
static ss_status unit_area_scale(int n, const double *M, double *area, ss_error *err) {
  *area = 0;
  for (int x = 0; x < n; x++) *area += M[x];
  if (!(*area > 0 && isfinite(*area)))
    return ss_fail(err, SS_ERR_INVALID, "probes: the shape's masses sum to %g (need a positive finite area)", *area);
  return SS_OK;
}

/* Normalise the columns of F in L²(M), then fill out (A, and the packed operators when asked; the
 * orientation operators of the first n_orient columns).
 * Scale: with the shape scaled by s, Φ goes as 1/s, M as s² and a unit-L²(M) function as 1/s, so the
 * coefficients A = Φᵀ M f are scale-free but D = Φᵀ M diag(f) Φ goes as 1/s: the commutativity term of
 * Eq. (1) would weigh 1/s² against the data term (x1e4 made it vanish, x1e-4 swamp the descriptors).
 * The operators are therefore those of the shape scaled to unit area, D·√area (f·√area is the
 * function normalised at unit area; Φ and M scale back); A is the same at any scale. */
static ss_status finish(const ss_mesh *mesh, int k, const double *evecs, const double *M, double *F, int p,
                        int with_operators, int n_orient, ss_fmap_probes *out, ss_error *err) {
  const int n = mesh->nv;
  double area = 0;
  if (with_operators) {
    ss_status sa = unit_area_scale(n, M, &area, err);
    if (sa) return sa;
  }
  normalise_columns(n, M, p, F, NULL);
  memset(out, 0, sizeof *out);
  out->k = k, out->p = p, out->nd = with_operators ? p : 0;
  out->A = malloc(sizeof(double) * (size_t)k * (p > 0 ? p : 1));
  if (with_operators) out->P = malloc(sizeof(double) * (size_t)k * (k + 1) / 2 * (p > 0 ? p : 1));
  ss_status st = SS_OK;
  if (!out->A || (with_operators && !out->P)) st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
  if (!st) st = ss_fmap_project(n, k, evecs, M, p, F, out->A, err);
  if (!st && with_operators) st = ss_fmap_mult_operators_packed(n, k, evecs, M, p, F, out->P, err);
  if (!st && with_operators) cblas_dscal((int)((size_t)k * (k + 1) / 2 * p), sqrt(area), out->P, 1);
  if (!st && with_operators && n_orient > 0) {
    /* the orientation operators of the first n_orient columns, those of the shape
     * at unit area (φ and the unit-L²(M) functions scale back by √area each, O is trilinear in them) */
    out->no = n_orient < p ? n_orient : p;
    if (!(out->O = malloc(sizeof(double) * (size_t)k * k * out->no))) st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
    /* every face wound the same way on both shapes: each mesh's outward orientation (a scan wound
     * inward, or partly each way, gives the same operators) */
    int *Fo = NULL;
    if (!st) st = ssi_mesh_outward_copy(mesh, &Fo, err);
    ss_mesh outward = *mesh;
    if (Fo) outward.F = Fo;
    if (!st) st = ss_fmap_orientation_operators(&outward, k, evecs, out->no, F, out->O, err);
    free(Fo);
    if (!st) cblas_dscal((int)((size_t)k * k * out->no), area * sqrt(area), out->O, 1);
  }
  if (st) ss_fmap_probes_free(out);
  return st;
}

/* Common start of the builders: options (defaults for NULL) checked into *o, the shape checked
 * against them, *out zeroed. */
static ss_status start(const ss_fmap_shape *s, const ss_fmap_match_options *opts, ss_fmap_probes *out,
                       ss_fmap_match_options *o, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "probes: NULL output");
  memset(out, 0, sizeof *out);
  ss_status st = ssi_fmap_options_resolve(opts, o, err);
  return st ? st : ssi_fmap_check_shape(s, "of the probes", ssi_fmap_descr_k(o), err);
}

/* the shape's lumped masses: its own, or barycentric ones in *own */
static ss_status masses(const ss_fmap_shape *s, double **own, const double **M, ss_error *err) {
  *own = NULL;
  *M = s->M;
  if (s->M) return SS_OK;
  if (!(*own = malloc(sizeof(double) * (size_t)s->mesh->nv))) return ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
  ss_status st = ss_mass_lumped(s->mesh, SS_MASS_BARYCENTRIC, *own, err);
  *M = *own;
  return st;
}

/* T (k(k+1)/2 x kt): the packed operators of the first kt eigenfunctions */
static ss_status triple_products(int n, int k, int kt, const double *evecs, const double *M, double **T, ss_error *err) {
  if (!(*T = malloc(sizeof(double) * (size_t)k * (k + 1) / 2 * kt))) return ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
  ss_status st = ss_fmap_mult_operators_packed(n, k, evecs, M, kt, evecs, *T, err);
  if (st) free(*T), *T = NULL;
  return st;
}

/* the WKS columns of options o (descriptor basis kd) as a probe block: what a cache entry holds */
static ss_status wks_block(const ss_fmap_shape *s, const ss_fmap_match_options *o, const double *M, int with_operators,
                           ss_fmap_probes *out, ss_error *err) {
  const int n = s->mesh->nv, kd = ssi_fmap_descr_k(o), nwks = (o->n_energies + o->descr_step - 1) / o->descr_step;
  double *F = NULL;
  int p = 0;
  ss_status st = kept_columns(n, kd, s->evals, s->evecs, o, 1, NULL, 0, o->n_energies, &F, &p, NULL, err);
  if (!st) st = finish(s->mesh, o->k, s->evecs, M, F, p, with_operators, o->w_orient > 0 ? nwks : 0, out, err);
  free(F);
  return st;
}

static const ss_fmap_probe_cache *cached_wks(const ss_fmap_shape *s, const ss_fmap_match_options *o, int with_operators) {
  const int kd = ssi_fmap_descr_k(o);
  for (int i = 0; i < s->ncache && s->cache; i++) {
    const ss_fmap_probe_cache *c = &s->cache[i];
    if (c->nwks > 0 && c->A && c->k == o->k && c->kd == kd && c->n_energies == o->n_energies &&
        c->descr_step == o->descr_step && c->sigma_factor == o->sigma_factor &&
        (!with_operators || (c->P && (!(o->w_orient > 0) || c->O))))
      return c;
  }
  return NULL;
}

static const ss_fmap_probe_cache *cached_triple(const ss_fmap_shape *s, int k, int kd) {
  for (int i = 0; i < s->ncache && s->cache; i++)
    if (s->cache[i].T && s->cache[i].k == k && s->cache[i].kt >= kd) return &s->cache[i];
  return NULL;
}

int ssi_fmap_cache_covers(const ss_fmap_shape *s, const ss_fmap_match_options *o, int with_operators) {
  return cached_wks(s, o, with_operators) && (!with_operators || cached_triple(s, o->k, ssi_fmap_descr_k(o)));
}

void ss_fmap_probe_cache_free(ss_fmap_probe_cache *c) {
  if (!c) return;
  free(c->A), free(c->P), free(c->O), free(c->T);
  memset(c, 0, sizeof *c);
}

ss_status ss_fmap_probe_cache_compute(const ss_fmap_shape *s, const ss_fmap_match_options *opts, int with_triple,
                                      int kt_max, ss_fmap_probe_cache *out, ss_error *err) {
  ss_fmap_match_options o;
  ss_fmap_probes blk = {0};
  ss_status st = start(s, opts, &blk, &o, err);
  if (!out) return ss_fail(err, SS_ERR_INVALID, "probe cache: NULL output");
  memset(out, 0, sizeof *out);
  if (st) return st;
  const int kd = ssi_fmap_descr_k(&o), kt = kt_max > kd ? kt_max : kd;
  if (kt > s->kev) return ss_fail(err, SS_ERR_INVALID, "probe cache: %d eigenpairs, %d needed", s->kev, kt);
  double *own = NULL;
  const double *M = NULL;
  if ((st = masses(s, &own, &M, err))) return st;
  out->k = o.k, out->kd = kd, out->n_energies = o.n_energies, out->descr_step = o.descr_step;
  out->sigma_factor = o.sigma_factor;
  if (!(st = wks_block(s, &o, M, 1, &blk, err))) {
    out->nwks = blk.p, out->A = blk.A, out->P = blk.P, out->O = blk.O;
    memset(&blk, 0, sizeof blk);
  }
  if (!st && with_triple && !(st = triple_products(s->mesh->nv, o.k, kt, s->evecs, M, &out->T, err))) out->kt = kt;
  if (st) ss_fmap_probe_cache_free(out);
  free(own);
  return st;
}

/* out = [a | b] column blocks (A, P; O from whichever block has them); a and b are freed */
static ss_status append_block(int k, ss_fmap_probes *a, ss_fmap_probes *b, ss_error *err) {
  if (b->p == 0) { ss_fmap_probes_free(b); return SS_OK; }
  if (a->p == 0) { ss_fmap_probes_free(a); *a = *b; memset(b, 0, sizeof *b); return SS_OK; }
  const size_t kk = (size_t)k * (k + 1) / 2;
  const int p = a->p + b->p, with_ops = a->nd > 0 || b->nd > 0;
  double *A = realloc(a->A, sizeof(double) * (size_t)k * p);
  if (A) a->A = A;
  double *P = with_ops ? realloc(a->P, sizeof(double) * kk * p) : NULL;
  if (P) a->P = P;
  if (!A || (with_ops && !P)) { ss_fmap_probes_free(b); return ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); }
  memcpy(a->A + (size_t)k * a->p, b->A, sizeof(double) * (size_t)k * b->p);
  if (with_ops) memcpy(a->P + kk * a->nd, b->P, sizeof(double) * kk * b->nd);
  if (b->no > 0) a->no = b->no, a->O = b->O, b->O = NULL;
  a->p = p, a->nd += b->nd;
  ss_fmap_probes_free(b);
  return SS_OK;
}

/* The landmark columns: synthesised, normalised, projected; their operators from the triple
 * products by their spectral coefficients (exactly the operator of the synthesised function) */
static ss_status landmark_block(const ss_fmap_shape *s, const ss_fmap_match_options *o, const double *M, int nl, const int *lm,
                                int with_operators, ss_fmap_probes *out, ss_error *err) {
  const int n = s->mesh->nv, k = o->k, kd = ssi_fmap_descr_k(o), ne = o->n_energies;
  const size_t kk = (size_t)k * (k + 1) / 2;
  double *coef = malloc(sizeof(double) * (size_t)kd * nl), *F = NULL, *fc = NULL, *norms = NULL, *Tl = NULL;
  const double *T = NULL;
  int p = 0;
  ss_status st = SS_OK;
  memset(out, 0, sizeof *out);
  if (!coef) return ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
  /* landmark deltas in the spectral domain: φ_i(l) (the L²-delta δ_l / M_l projects to these) */
  for (int l = 0; l < nl; l++)
    for (int i = 0; i < kd; i++) coef[i + (size_t)kd * l] = s->evecs[lm[l] + (size_t)n * i];
  if ((st = kept_columns(n, kd, s->evals, s->evecs, o, 1, coef, ne, ne * (1 + nl), &F, &p, &fc, err))) goto done;
  if (!(norms = malloc(sizeof(double) * (size_t)(p > 0 ? p : 1))) || !(out->A = malloc(sizeof(double) * (size_t)k * (p > 0 ? p : 1)))) {
    st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
    goto done;
  }
  normalise_columns(n, M, p, F, norms);
  out->k = k, out->p = p;
  if ((st = ss_fmap_project(n, k, s->evecs, M, p, F, out->A, err))) goto done;
  if (with_operators && p > 0) {
    double area;
    if ((st = unit_area_scale(n, M, &area, err))) goto done;
    const ss_fmap_probe_cache *c = cached_triple(s, k, kd);
    if (c) T = c->T;
    else if (!(st = triple_products(n, k, kd, s->evecs, M, &Tl, err))) T = Tl;
    if (st) goto done;
    for (int j = 0; j < p; j++) cblas_dscal(kd, sqrt(area) / norms[j], fc + (size_t)kd * j, 1);
    if (!(out->P = malloc(sizeof(double) * kk * p))) { st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); goto done; }
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, (int)kk, p, kd, 1.0, T, (int)kk, fc, kd, 0.0, out->P, (int)kk);
    out->nd = p;
  }
done:
  if (st) ss_fmap_probes_free(out);
  free(coef), free(F), free(fc), free(norms), free(Tl);
  return st;
}

ss_status ss_fmap_base_probes(const ss_fmap_shape *s, int nl, const int *lm, const ss_fmap_match_options *opts,
                              int with_operators, ss_fmap_probes *out, ss_error *err) {
  ss_fmap_match_options o;
  ss_status st = start(s, opts, out, &o, err);
  if (st) return st;
  const int n = s->mesh->nv, k = o.k;
  if (nl < 0 || (nl > 0 && !lm)) return ss_fail(err, SS_ERR_INVALID, "probes: missing landmarks");
  for (int l = 0; l < nl; l++)
    if (lm[l] < 0 || lm[l] >= n) return ss_fail(err, SS_ERR_INVALID, "landmark %d: vertex %d out of range [0,%d)", l, lm[l], n);
  if (s->ndescr < 0 || (s->ndescr > 0 && !s->descr))
    return ss_fail(err, SS_ERR_INVALID, "probes: %d descriptors without their values", s->ndescr);
  for (size_t i = 0; i < (size_t)n * (size_t)(s->ndescr > 0 ? s->ndescr : 0); i++)
    if (!isfinite(s->descr[i]))
      return ss_fail(err, SS_ERR_INVALID, "probes: descriptor %d is not finite at vertex %d", (int)(i / (size_t)n),
                     (int)(i % (size_t)n));
  if (o.no_wks && nl == 0 && s->ndescr == 0) return ss_fail(err, SS_ERR_INVALID, "probes: no WKS, no landmark and no descriptor");
  double *own = NULL, *F = NULL;
  const double *M = NULL;
  ss_fmap_probes blk = {0};
  if ((st = masses(s, &own, &M, err))) goto done;
  /* the blocks [WKS | landmarks | own descriptors], each built alone: the WKS (with its orientation
   * operators) from the shape's cache when it has the entry */
  if (!o.no_wks) {
    const ss_fmap_probe_cache *c = cached_wks(s, &o, with_operators);
    if (c) {
      const size_t kk = (size_t)k * (k + 1) / 2;
      out->k = k, out->p = c->nwks, out->nd = with_operators ? c->nwks : 0;
      out->no = with_operators && o.w_orient > 0 ? c->nwks : 0;
      out->A = malloc(sizeof(double) * (size_t)k * c->nwks);
      out->P = out->nd ? malloc(sizeof(double) * kk * c->nwks) : NULL;
      out->O = out->no ? malloc(sizeof(double) * (size_t)k * k * c->nwks) : NULL;
      if (!out->A || (out->nd && !out->P) || (out->no && !out->O)) { st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); goto done; }
      memcpy(out->A, c->A, sizeof(double) * (size_t)k * c->nwks);
      if (out->nd) memcpy(out->P, c->P, sizeof(double) * kk * c->nwks);
      if (out->no) memcpy(out->O, c->O, sizeof(double) * (size_t)k * k * c->nwks);
    } else if ((st = wks_block(s, &o, M, with_operators, out, err)))
      goto done;
  }
  if (nl > 0) {
    if ((st = landmark_block(s, &o, M, nl, lm, with_operators, &blk, err))) goto done;
    if ((st = append_block(k, out, &blk, err))) goto done;
  }
  if (s->ndescr > 0) { /* the shape's own descriptors after the kept columns, as they are */
    if (!(F = malloc(sizeof(double) * (size_t)n * s->ndescr))) { st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); goto done; }
    memcpy(F, s->descr, sizeof(double) * (size_t)n * s->ndescr);
    /* without the WKS, as many of them as the WKS columns they replace get orientation operators */
    const int nwks = (o.n_energies + o.descr_step - 1) / o.descr_step;
    const int n_orient = o.no_wks && o.w_orient > 0 ? (s->ndescr < nwks ? s->ndescr : nwks) : 0;
    if ((st = finish(s->mesh, k, s->evecs, M, F, s->ndescr, with_operators, n_orient, &blk, err))) goto done;
    if ((st = append_block(k, out, &blk, err))) goto done;
  }
  if (out->p == 0) st = ss_fail(err, SS_ERR_INVALID, "probes: no WKS, no landmark and no descriptor");
done:
  if (st) ss_fmap_probes_free(out);
  ss_fmap_probes_free(&blk);
  free(own), free(F);
  return st;
}

ss_status ss_fmap_extra_probes(const ss_fmap_shape *s, int nl, int nextra, const double *extra, ss_probe_filter filter,
                               const ss_fmap_match_options *opts, int with_operators, ss_fmap_probes *out,
                               ss_error *err) {
  ss_fmap_match_options o;
  ss_status st = start(s, opts, out, &o, err);
  if (st) return st;
  if (nl < 0 || nextra < 0 || (nextra > 0 && !extra)) return ss_fail(err, SS_ERR_INVALID, "probes: missing extra probes");
  if (filter != SS_PROBE_RAW && filter != SS_PROBE_WAVE) return ss_fail(err, SS_ERR_INVALID, "probes: unknown filter %d", (int)filter);
  const int n = s->mesh->nv, k = o.k, kd = ssi_fmap_descr_k(&o), ne = o.n_energies;
  double *own = NULL, *coef = NULL, *F = NULL;
  const double *M = NULL;
  int p = 0;
  if ((st = masses(s, &own, &M, err))) goto done;
  if (filter == SS_PROBE_WAVE) {
    if (!(coef = malloc(sizeof(double) * (size_t)kd * (nextra > 0 ? nextra : 1)))) {
      st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
      goto done;
    }
    if ((st = ss_fmap_project(n, kd, s->evecs, M, nextra, extra, coef, err))) goto done;
    if ((st = kept_columns(n, kd, s->evals, s->evecs, &o, 1 + nl, coef, ne * (1 + nl), ne * (1 + nl + nextra), &F, &p, NULL,
                           err)))
      goto done;
  } else {
    if (!(F = malloc(sizeof(double) * (size_t)n * (nextra > 0 ? nextra : 1)))) {
      st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
      goto done;
    }
    memcpy(F, extra, sizeof(double) * (size_t)n * nextra);
    p = nextra;
  }
  st = finish(s->mesh, k, s->evecs, M, F, p, with_operators, 0, out, err);
done:
  free(own), free(coef), free(F);
  return st;
}
