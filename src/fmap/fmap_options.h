/* Internal: the one place where ss_fmap_match_options are defaulted and checked, and where a shape
 * handed to the functional-map code is checked (probes, solve, point map and the pipeline all call
 * these). */
#ifndef SS_FMAP_OPTIONS_INTERNAL_H
#define SS_FMAP_OPTIONS_INTERNAL_H

#include "specseg/fmap.h"

/* *o = *opts, or the defaults when opts is NULL; then the checks of ssi_fmap_check_options. */
ss_status ssi_fmap_options_resolve(const ss_fmap_match_options *opts, ss_fmap_match_options *o, ss_error *err);
/* k >= 3, energies >= 1, descr_step >= 1, sigma_factor > 0, finite non-negative weights, zoomout_step
 * >= 1, zoomout_kmax 0 or >= k. */
ss_status ssi_fmap_check_options(const ss_fmap_match_options *o, ss_error *err);
/* The shape has its mesh, eigenpairs and at least `need` of them. name: "X", "Y", ... for messages. */
ss_status ssi_fmap_check_shape(const ss_fmap_shape *s, const char *name, int need, ss_error *err);
/* Eigenpairs the options need on each shape: max(k, zoomout_kmax, descr_k). */
int ssi_fmap_basis_needed(const ss_fmap_match_options *o);
/* Eigenpairs the probe functions are synthesised from: max(k, descr_k). */
int ssi_fmap_descr_k(const ss_fmap_match_options *o);
/* 1 when s's probe cache has every shape-only part of ss_fmap_base_probes at options o (with or
 * without operators): its WKS entry and triple products (fmap_probes.c) */
int ssi_fmap_cache_covers(const ss_fmap_shape *s, const ss_fmap_match_options *o, int with_operators);

/* ZoomOut of a pair as the options ask (zoomout_samples): plain, or on ns samples of the target
 * against every source vertex (ss_zoomout_samples, ss_zoomout_sampled: least squares, one iteration
 * on every vertex at the end) with the source's partition made once, so that several starts of one
 * pair share them. ns <= 0 or ns >= the target's vertex count: plain ZoomOut. */
typedef struct ssi_zoomout_plan {
  int n_S, n_T;
  ss_zoomout_sample smp; /* sub_T = NULL: plain */
  int *sub_S, *sub_T, *near_T, *near_S, *part_S;
  double *w_T, *w_S;
} ssi_zoomout_plan;
ss_status ssi_zoomout_plan_new(const ss_mesh *mS, const double *M_S, const double *evecs_S, const ss_mesh *mT,
                               const double *M_T, int ns, int kmax, ssi_zoomout_plan *p, ss_error *err);
ss_status ssi_zoomout_plan_run(const ssi_zoomout_plan *p, const double *evecs_S, const double *evecs_T, const double *M_T,
                               int k0, const double *C0, int kmax, int step, int *map, double *C_out, ss_error *err);
void ssi_zoomout_plan_free(ssi_zoomout_plan *p);

#endif
