/* Internals of the landmark-free pairing shared by its files (centre_signature.c, pairing_search.c,
 * pairing_orientation.c, autopair.c) and with tests and benchmarks. */
#ifndef SS_AUTOPAIR_INTERNAL_H
#define SS_AUTOPAIR_INTERNAL_H

#include "specseg/fmap.h"
#include "specseg/match.h"

/* ---- the search (pairing_search.c) ---------------------------------------------------------- */

#define SSI_TOPK 8 /* leaves kept by the exact search (self-symmetry candidates, runner-ups) */

typedef struct ssi_search {
  int na, nb;
  const double *U;  /* na x nb unary costs, U[a * nb + b] (weighted) */
  const double *DA, *DB;
  double wg;        /* weight of a squared distance difference */
  const double *minU; /* minU[t] = Σ_{a ≥ t} min_b U[a][b] */
  int *cur, *used;
  int ntop;                 /* leaves kept (1..SSI_TOPK) */
  double top_e[SSI_TOPK];   /* ascending */
  int *top_p[SSI_TOPK];
} ssi_search;

/* Energy of an assignment p (A index -> B index); share (may be NULL): per-centre shares. */
double ssi_full_energy(const ssi_search *S, const int *p, double *share);

/* qsort's comparator of doubles, ascending (on records, by their first double) */
int ssi_dbl_cmp(const void *a, const void *b);

/* The number of injections of na centres into nb (the exact search's leaves). */
double ssi_count_injections(int na, int nb);

/* Runs the search: the exact branch and bound (exact) or the relaxation (Hungarian + local moves),
 * keeping ntop leaves; self: A with itself (the identity excluded); *status = 1: out of memory. */
void ssi_run_search(ssi_search *S, int exact, int ntop, int self, int *status);

/* Unary costs of A's centres against Q's and their suffix minima (the search's bound). */
void ssi_fill_unary(ssi_search *S, double *U, double *minU, const ss_centre_signature *A, const ss_centre_signature *Q,
                    double w_descr);

/* A search for A's centres over the caller's buffers (U, minU: fill_unary's; cur, used: nb each;
 * buf: na · SSI_TOPK, the kept leaves). */
void ssi_init_search(ssi_search *S, const ss_centre_signature *A, const ss_autopair_options *o, double *U, double *minU,
                     int *cur, int *used, int *buf);

/* ---- the orientation tests (pairing_orientation.c) ------------------------------------------- */

/* The orientation test (match.h) of the pairing p: centre a of A -> centre p[a] of B (A->m <= B->m):
 * the orientation score of the small functional map's point map A -> B. */
ss_status ssi_autopair_orient_score(const ss_centre_signature *A, const ss_centre_signature *B, const int *p,
                                    const ss_autopair_options *o, double *score, ss_error *err);

/* The second orientation test (ss_autopair_options.recheck_*) of the pairing p. */
ss_status ssi_autopair_recheck_score(const ss_centre_signature *A, const ss_centre_signature *B, const int *p,
                                     const ss_autopair_options *o, double *score, ss_error *err);

/* Orientation of a point map T: A -> B (A's nv entries): over A's faces whose image triangle is not
 * degenerate, (preserved − reversed) / count, against B's outward normals. */
double ssi_map_orientation(const ss_centre_signature *A, const ss_centre_signature *B, const int *T);

/* The share of A's segments (those with a counted face) on which T scores below thr (the orientation
 * score of each segment's faces, as above); seg: 2·A->m scratch, on return A->m per-segment scores
 * (NAN: none counted); *smin (may be NULL): the least segment score. 1 when no segment is scored. */
double ssi_map_orientation_reversed(const ss_centre_signature *A, const ss_centre_signature *B, const int *T, double thr,
                                    double *seg, double *smin);

/* Both candidates' orientation scores r1, r2 (orient_k = k, orient_descr_k = descr_k, orient_keep =
 * keep) and the decision's median margin med (> 0: p1), as ss_pair_centres_auto computes them. */
ss_status ssi_orient_pair(const ss_centre_signature *A, const ss_centre_signature *B, const int *p1, const int *p2, int k,
                          int descr_k, double keep, double *r1, double *r2, double *med, ss_error *err);

/* The orientation test's functional-map options for shapes with kmin eigenpairs. */
void ssi_orient_fmap_options(int k, int descr_k, int kmin, ss_fmap_match_options *fo);

/* kept[a] (A->m) = 1 for the round(keep · m) (at least 3) centres of A farthest on average from the
 * others (the protrusions: head, hands, feet on a body), 0 for the others; all when keep >= 1. */
void ssi_kept_centres(const ss_centre_signature *A, double keep, int *kept);

/* The median over A's m segments of s1 − s2 (segments scored in both), 0 when none; tmp: m. */
double ssi_median_margin(int m, const double *s1, const double *s2, double *tmp);

/* ---- the orientation test with probes shared by the candidates ------------------------------- *
 * Every candidate's functional map has the same probes on A (WKS + the kept centres of A, in A's
 * order) and, on B, the WKS and the wave-kernel maps of B's centres in the candidate's order: B's
 * probes are built once for all of its centres and each candidate takes its columns (the probe list
 * keeps every descr_step-th of n_energies columns per item, the same columns in every item when
 * descr_step divides n_energies). What ss_fmap_match would compute, for a fraction of the cost. */
typedef struct ssi_orient_ctx {
  const ss_centre_signature *A, *B;
  ss_fmap_match_options fo;
  ss_fmap_shape sA, sB;
  ss_fmap_probes pA, pB; /* pA: WKS + A's kept centres; pB: WKS + every centre of B (when built here) */
  const double *bA, *bP;  /* B's probes: pB's, or its signature's (basis bk >= fo.k) */
  int bk;
  ss_fmap_weights w;
  int na, nb, per;        /* kept centres of A, centres of B, probe columns per item */
  int *kept;              /* na indices of A's kept centres, ascending */
  double *Abuf, *Pbuf;    /* a candidate's B probes */
  int *T;
} ssi_orient_ctx;

/* The shared-probe orientation test of A -> B (basis k, descriptors from descr_k eigenpairs, the
 * keep share of A's centres as probes); free with ssi_orient_ctx_free. */
ss_status ssi_orient_ctx_new(const ss_centre_signature *A, const ss_centre_signature *B, int k, int descr_k, double keep,
                             ssi_orient_ctx *c, ss_error *err);

/* The point map A -> B of candidate p (A index -> B index) into c->T, its orientation score and
 * (seg: 2·A->m scratch, may be NULL) the per-segment scores. */
ss_status ssi_orient_ctx_score(ssi_orient_ctx *c, const int *p, double *score, double *seg, ss_error *err);

/* Frees c's buffers (c zeroed). */
void ssi_orient_ctx_free(ssi_orient_ctx *c);

/* ---- the oriented polish (pairing_polish.c) -------------------------------------------------- */

/* The oriented polish of the pairing p (A index -> B index, A = oc->A; energy *E under S, first-test
 * whole-shape score *r under oc): up to rounds times, the single moves (two A centres exchange their
 * images, or one moves to a free B centre) that lower the energy are scored in ascending energy, at
 * most SSI_TOPK a round, and the first whose score is at least *r − tol and above r_rejected, and
 * which is not the pairing rejected (may be NULL; the left / right decision's loser), is applied
 * (p, *E, *r updated). *moves: moves applied. Scratch: cand A->m, inv B->m, mv 2·A->m·B->m. */
ss_status ssi_polish_oriented(ssi_orient_ctx *oc, const ssi_search *S, int *p, double *E, double *r, int rounds, double tol,
                              const int *rejected, double r_rejected, int *cand, int *inv, double *mv, int *moves,
                              ss_error *err);

#endif
