/* Private: what the files of the matching pipeline (src/match/match*.c) call in each other. */
#ifndef SS_MATCH_INTERNAL_H
#define SS_MATCH_INTERNAL_H

#include "specseg/match.h"
#include "fmap/fmap_options.h"
#include "fmap/fmap_work.h"

/* Appends "; msg" (msg alone when the first) to r->notes, truncating. */
void ssi_match_note(ss_match_result *r, const char *msg);

/* The fmap options of a match's two starts: [0] STD, [1] the segment-aided one (its own descriptor
 * basis); returns how many differ in what a probe cache holds (1 or 2). */
int ssi_match_start_options(const ss_match_options *o, ss_fmap_match_options fo[2]);

/* The probe cache entries of both shapes that the shapes do not carry (NULL, 0 where they do), side
 * by side when both need them (ssi_run_both); X's error first. */
ss_status ssi_match_probe_caches_both(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_match_options *o,
                                      ss_fmap_probe_cache **cx, int *nx, ss_fmap_probe_cache **cy, int *ny,
                                      ss_error *err);

/* One match of two prepared shapes from nl >= 1 landmarks (lmX, lmY: their vertices): the segments
 * paired from the landmarks (or pairs_in as given, checked; NULL: paired here), the STD and the
 * segment-aided functional maps, the point map and its refinement (ss_match_options.refine). */
ss_status ssi_match_core(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                         const ss_segment_pairs *pairs_in, const ss_match_options *opts_in, ss_match_result *out,
                         ss_error *err);

/* ssi_match_core with a ZoomOut plan made by the caller for these shapes and options (ssi_match_plan;
 * NULL: made here): the hypotheses of one match share it, as it depends on the shapes alone; and
 * with the functional-map solver's buffers in work (NULL: its own), which they share too. */
ss_status ssi_match_core_planned(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX,
                                 const int *lmY, const ss_segment_pairs *pairs_in, const ss_match_options *opts_in,
                                 const ssi_zoomout_plan *plan, ssi_fmap_work *work, ss_match_result *out, ss_error *err);

/* the ZoomOut size of a match: fmap.zoomout_kmax when it refines beyond fmap.k, else fmap.k */
int ssi_match_zoomout_size(const ss_match_options *o);

/* The ZoomOut plan ssi_match_core would make for X -> Y under o (an empty one, p->n_S = 0, when o
 * refines nothing or the shapes have too few eigenpairs for it). */
ss_status ssi_match_plan(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_match_options *o,
                         ssi_zoomout_plan *p, ss_error *err);

#endif
