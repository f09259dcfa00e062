/* Pairing of the segments of two shapes (paper §6.1): critical points are compared through their
 * exact geodesic distances to corresponding landmarks, on the streamlined (work) shapes. */
#include "specseg/match.h"
#include "specseg/geodesic.h"
#include "util/side_by_side.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ss_segment_pairs_free(ss_segment_pairs *p) {
  if (!p) return;
  free(p->sx);
  free(p->sy);
  free(p->energy);
  memset(p, 0, sizeof *p);
}

void ss_pairing_paper_options(ss_pairing_options *o) {
  memset(o, 0, sizeof *o);
  o->min_ratio = 1.0;
  o->mutual = 0;
  o->max_rel_energy = 0.0;
  o->min_landmarks = 1;
}

void ss_pairing_default_options(ss_pairing_options *o) {
  ss_pairing_paper_options(o);
  o->min_ratio = 2.0;     /* docs/tuning.md */
  o->min_landmarks = 4;
  o->min_map_share = 0.5; /* docs/tuning.md */
}

ss_status ss_segment_pairs_check_map(const ss_segmentation *X, const ss_segmentation *Y, const double *MX,
                                     const int *map, double min_share, ss_segment_pairs *pairs, double *share,
                                     int *dropped, ss_error *err) {
  if (dropped) *dropped = 0;
  if (!X || !Y || !X->labels || !Y->labels || !map || !pairs || pairs->n < 0 || (pairs->n > 0 && (!pairs->sx || !pairs->sy)))
    return ss_fail(err, SS_ERR_INVALID, "pairing: map check: incomplete input");
  const int n = pairs->n, mx = X->m;
  for (int p = 0; p < n; p++)
    if (pairs->sx[p] < 0 || pairs->sx[p] >= mx || pairs->sy[p] < 0 || pairs->sy[p] >= Y->m)
      return ss_fail(err, SS_ERR_INVALID, "pairing: map check: pair %d (%d, %d) out of range (%d, %d segments)", p,
                     pairs->sx[p], pairs->sy[p], mx, Y->m);
  /* per segment of X: its mass and the mass mapped into its partner (col: X segment -> pair) */
  int *col = malloc(sizeof(int) * (size_t)(mx > 0 ? mx : 1));
  double *tot = calloc((size_t)(n > 0 ? n : 1), sizeof(double)), *in = calloc((size_t)(n > 0 ? n : 1), sizeof(double));
  if (!col || !tot || !in) {
    free(col), free(tot), free(in);
    return ss_fail(err, SS_ERR_NOMEM, "pairing: out of memory");
  }
  for (int s = 0; s < mx; s++) col[s] = -1;
  for (int p = 0; p < n; p++) col[pairs->sx[p]] = p;
  for (int i = 0; i < X->nv; i++) {
    int s = X->labels[i];
    if (s < 0 || s >= mx || col[s] < 0) continue;
    int p = col[s], y = map[i];
    double w = MX ? MX[i] : 1.0;
    tot[p] += w;
    if (y >= 0 && y < Y->nv && Y->labels[y] == pairs->sy[p]) in[p] += w;
  }
  int q = 0;
  for (int p = 0; p < n; p++) {
    double sh = tot[p] > 0 ? in[p] / tot[p] : 0.0;
    if (share) share[p] = sh;
    if (!(sh >= min_share)) continue;
    pairs->sx[q] = pairs->sx[p], pairs->sy[q] = pairs->sy[p];
    if (pairs->energy) pairs->energy[q] = pairs->energy[p];
    q++;
  }
  if (dropped) *dropped = n - q;
  pairs->n = q;
  free(col), free(tot), free(in);
  return SS_OK;
}

ss_status ss_pair_critical_points(int mx, int my, int nl, const double *dX, const double *dY,
                                  ss_segment_pairs *out, ss_error *err) {
  return ss_pair_critical_points_conf(mx, my, nl, dX, dY, NULL, out, err);
}

static double pair_energy2(int a, int b, int na, int nb, int nl, const double *dA, const double *dB) {
  double s = 0;
  for (int i = 0; i < nl; i++) {
    double d = dA[a + (size_t)na * i] - dB[b + (size_t)nb * i];
    s += d * d;
  }
  return s;
}

ss_status ss_pair_critical_points_conf(int mx, int my, int nl, const double *dX, const double *dY,
                                       const ss_pairing_options *po, ss_segment_pairs *out, ss_error *err) {
  ss_pairing_options paper;
  ss_pairing_paper_options(&paper);
  if (!po) po = &paper;
  if (!out) return ss_fail(err, SS_ERR_INVALID, "pairing: NULL output");
  memset(out, 0, sizeof *out);
  if (mx < 0 || my < 0 || nl < 1 || (mx > 0 && !dX) || (my > 0 && !dY))
    return ss_fail(err, SS_ERR_INVALID, "pairing: bad sizes (%d, %d critical points, %d landmarks)", mx, my, nl);
  out->nx = mx;
  out->ny = my;
  /* the shape with fewer critical points chooses; A chooses among B */
  int swap = mx > my;
  int na = swap ? my : mx, nb = swap ? mx : my;
  const double *dA = swap ? dY : dX, *dB = swap ? dX : dY;
  int *choice = malloc(sizeof(int) * (size_t)(na > 0 ? na : 1));
  double *energy = malloc(sizeof(double) * (size_t)(na > 0 ? na : 1));
  int *owner = malloc(sizeof(int) * (size_t)(nb > 0 ? nb : 1)); /* index in A that keeps each b */
  if (!choice || !energy || !owner) {
    free(choice), free(energy), free(owner);
    return ss_fail(err, SS_ERR_NOMEM, "pairing: out of memory");
  }
  for (int b = 0; b < nb; b++) owner[b] = -1;
  for (int a = 0; a < na; a++) {
    double best = INFINITY, second = INFINITY;
    int bi = -1;
    for (int b = 0; b < nb; b++) {
      double s = pair_energy2(a, b, na, nb, nl, dA, dB);
      if (s < best) second = best, best = s, bi = b; /* strict: ties go to the lower index */
      else if (s < second) second = s;
    }
    choice[a] = bi;
    energy[a] = sqrt(best);
    if (bi < 0) continue; /* non-finite distances everywhere (another component) */
    /* confidence: an ambiguous choice (second best too close) stays unpaired */
    if (po->min_ratio > 1 && !(sqrt(second) >= po->min_ratio * energy[a])) { choice[a] = -1; continue; }
    if (po->max_rel_energy > 0) {
      double r2 = 0;
      for (int i = 0; i < nl; i++) r2 += dA[a + (size_t)na * i] * dA[a + (size_t)na * i];
      if (!(energy[a] <= po->max_rel_energy * sqrt(r2 / nl))) { choice[a] = -1; continue; }
    }
    if (po->mutual) { /* a must be b*'s nearest among every chooser, not only among those that chose it */
      int mutual = 1;
      for (int a2 = 0; a2 < na && mutual; a2++)
        if (a2 != a) {
          double s2 = pair_energy2(a2, bi, na, nb, nl, dA, dB);
          if (s2 < best || (s2 == best && a2 < a)) mutual = 0;
        }
      if (!mutual) { choice[a] = -1; continue; }
    }
    /* conservative rule: the closest voter keeps y*; the others stay unpaired */
    if (owner[bi] < 0 || energy[a] < energy[owner[bi]]) owner[bi] = a;
  }
  int n = 0;
  for (int b = 0; b < nb; b++) n += owner[b] >= 0;
  out->sx = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
  out->sy = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
  out->energy = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
  if (!out->sx || !out->sy || !out->energy) {
    free(choice), free(energy), free(owner);
    ss_segment_pairs_free(out);
    return ss_fail(err, SS_ERR_NOMEM, "pairing: out of memory");
  }
  /* emit in increasing X segment order */
  int p = 0;
  if (!swap) {
    for (int a = 0; a < na; a++)
      if (choice[a] >= 0 && owner[choice[a]] == a) out->sx[p] = a, out->sy[p] = choice[a], out->energy[p++] = energy[a];
  } else {
    for (int b = 0; b < nb; b++)
      if (owner[b] >= 0) out->sx[p] = b, out->sy[p] = owner[b], out->energy[p++] = energy[owner[b]];
  }
  out->n = p;
  free(choice), free(energy), free(owner);
  return SS_OK;
}

/* Scaled distances from the nl landmarks (work vertices) to the m critical points of one shape:
 * d (m x nl). Read from crit_fields (the critical points' own fields, work nv x m) when given;
 * otherwise one full exact field per landmark, the landmarks in parallel. */
static ss_status landmark_fields(const ss_segmentation *s, const double *crit_fields, int nl, const int *lm_input,
                                 double *d, ss_error *err) {
  const ss_mesh *w = &s->work;
  int *src = malloc(sizeof(int) * (size_t)nl);
  double *field = crit_fields ? NULL : malloc(sizeof(double) * (size_t)w->nv * nl);
  ss_geodesic_mesh *gm = NULL;
  ss_status st = SS_OK;
  if (!src || (!crit_fields && !field)) {
    st = ss_fail(err, SS_ERR_NOMEM, "pairing: out of memory");
    goto done;
  }
  for (int i = 0; i < nl; i++) {
    if (lm_input[i] < 0 || lm_input[i] >= s->nv) {
      st = ss_fail(err, SS_ERR_INVALID, "pairing: landmark %d: vertex %d out of range [0,%d)", i, lm_input[i], s->nv);
      goto done;
    }
    src[i] = s->psi[lm_input[i]];
    if (src[i] < 0) {
      st = ss_fail(err, SS_ERR_INVALID,
                   "pairing: landmark %d: vertex %d is on no segmented part of the shape (a component under 1%% of "
                   "the area, a crumb, gets no segmentation of its own); put the landmarks on its main components",
                   i, lm_input[i]);
      goto done;
    }
  }
  double scale = 1.0 / sqrt(ss_mesh_area(w));
  if (crit_fields) {
    for (int i = 0; i < nl; i++)
      for (int c = 0; c < s->m; c++) d[c + (size_t)s->m * i] = crit_fields[src[i] + (size_t)w->nv * c] * scale;
    goto done;
  }
  if ((st = ss_geodesic_mesh_build(w, &gm, err))) goto done;
  /* the fields are needed at the critical points only: each stops once they are settled */
  if ((st = ss_geodesic_fields_targets(gm, src, nl, s->crit, s->m, field, err))) goto done;
  for (int i = 0; i < nl; i++)
    for (int c = 0; c < s->m; c++) d[c + (size_t)s->m * i] = field[s->crit[c] + (size_t)w->nv * i] * scale;
done:
  ss_geodesic_mesh_free(gm);
  free(src);
  free(field);
  return st;
}

/* landmark_fields of one shape, as a task of ssi_run_both */
typedef struct fields_task {
  const ss_segmentation *s;
  const double *crit_fields;
  int nl;
  const int *lm;
  double *d;
} fields_task;
static ss_status fields_task_run(void *arg, ss_error *err) {
  fields_task *t = arg;
  return landmark_fields(t->s, t->crit_fields, t->nl, t->lm, t->d, err);
}

ss_status ss_pair_segments(const ss_segmentation *X, const ss_segmentation *Y, int nl, const int *lmX,
                           const int *lmY, ss_segment_pairs *out, ss_error *err) {
  return ss_pair_segments_conf(X, Y, nl, lmX, lmY, NULL, out, err);
}

static ss_status pair_segments_fields(const ss_segmentation *X, const double *fX, const ss_segmentation *Y,
                                     const double *fY, int nl, const int *lmX, const int *lmY,
                                     const ss_pairing_options *po, ss_segment_pairs *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "pairing: NULL output");
  memset(out, 0, sizeof *out);
  if (!X || !Y || !X->psi || !Y->psi || !X->crit || !Y->crit || X->m < 1 || Y->m < 1)
    return ss_fail(err, SS_ERR_INVALID, "pairing: incomplete segmentation");
  if (nl < 1 || !lmX || !lmY) return ss_fail(err, SS_ERR_INVALID, "pairing: needs at least one landmark");
  double *dX = malloc(sizeof(double) * (size_t)X->m * nl), *dY = malloc(sizeof(double) * (size_t)Y->m * nl);
  ss_status st = SS_OK;
  if (!dX || !dY) st = ss_fail(err, SS_ERR_NOMEM, "pairing: out of memory");
  /* both shapes' fields side by side, one thread each (when both propagate: a shape's few fields
   * spread over the threads leave one idle at the end) */
  fields_task tx = {X, fX, nl, lmX, dX}, ty = {Y, fY, nl, lmY, dY};
  if (!st) st = ssi_run_both(fields_task_run, &tx, fields_task_run, &ty, !fX && !fY, err);
  if (!st) st = ss_pair_critical_points_conf(X->m, Y->m, nl, dX, dY, po, out, err);
  free(dX);
  free(dY);
  return st;
}

ss_status ss_pair_segments_conf(const ss_segmentation *X, const ss_segmentation *Y, int nl, const int *lmX,
                                const int *lmY, const ss_pairing_options *po, ss_segment_pairs *out, ss_error *err) {
  return pair_segments_fields(X, NULL, Y, NULL, nl, lmX, lmY, po, out, err);
}

ss_status ss_pair_segments_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX,
                                    const int *lmY, const ss_pairing_options *po, ss_segment_pairs *out,
                                    ss_error *err) {
  if (!X || !Y) {
    if (out) memset(out, 0, sizeof *out);
    return ss_fail(err, SS_ERR_INVALID, "pairing: NULL shape");
  }
  return pair_segments_fields(&X->seg, X->crit_fields, &Y->seg, Y->crit_fields, nl, lmX, lmY, po, out, err);
}
