/* Internal: the dense functional-map solver's large buffers, kept across the systems of one match.
 *
 * A system at k = 50 is a 50 MB matrix, its solve with extra probes another 50 MB and a 25 MB single-
 * precision copy. A landmark-free match assembles and solves ~14 of them; fresh from the allocator,
 * each is mapped and faulted in again (glibc maps blocks above 32 MB every time unless the process
 * changes its malloc settings, as the CLI does; AddressSanitizer's allocator always does): a third of
 * a match's CPU time through the library or the Python package. With one work for the whole match
 * they are faulted in once. */
#ifndef SS_FMAP_WORK_INTERNAL_H
#define SS_FMAP_WORK_INTERNAL_H

#include "fmap/fmap_options.h"
#include "specseg/fmap.h"

typedef struct ssi_fmap_work {
  size_t m;    /* unknowns the buffers hold room for (0: none yet) */
  double *N;   /* m x m: the system's normal equations, lent to one live system at a time */
  double *own; /* m x m: a solve's system with extra probes */
  float *F;    /* m x m: a solve's single-precision factor */
} ssi_fmap_work;

void ssi_fmap_work_free(ssi_fmap_work *w);

/* ss_fmap_system_new with its matrix in w->N (w NULL: allocated as there). While the system lives, w
 * lends it w->N: one system per work at a time; free it with ss_fmap_system_free as any other. */
ss_status ssi_fmap_system_new_in(int k_S, int k_T, const double *evals_S, const double *evals_T, const ss_fmap_probes *S,
                                 const ss_fmap_probes *T, const ss_fmap_weights *w, ssi_fmap_work *work,
                                 ss_fmap_system **out, ss_error *err);

/* ss_fmap_system_solve with its copies in w->own and w->F (w NULL, or without room for the system:
 * allocated as there). The same solution to the bit. One solve per work at a time: unlike the public
 * solve, two solves that share a work must not run concurrently. */
ss_status ssi_fmap_system_solve_in(const ss_fmap_system *sys, const ss_fmap_probes *S_extra, const ss_fmap_probes *T_extra,
                                   double w_extra, int extra_dcomm, ssi_fmap_work *work, double *C, ss_error *err);

/* ss_fmap_match with its systems in work (NULL: as ss_fmap_match) and, when ZoomOut runs, the pair's
 * plan (NULL: one of its own; else made by ssi_zoomout_plan_new from Y to X with opts' zoomout_samples
 * and zoomout_kmax, which gives the same map to the bit). */
ss_status ssi_fmap_match_in(const ss_fmap_shape *X, const ss_fmap_shape *Y, int nl, const int *lmX, const int *lmY,
                            int nextra, const double *extraX, const double *extraY, ss_probe_filter extra_filter,
                            const ss_fmap_match_options *opts, ssi_fmap_work *work, const ssi_zoomout_plan *plan,
                            int *map, double *C, ss_error *err);

#endif
