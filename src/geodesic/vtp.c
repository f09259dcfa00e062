/* Exact polyhedral geodesics: continuous-Dijkstra window propagation (MMP windows) organised the
 * VTP way (Qin et al. 2016): windows wait in per-half-edge lists and cross their face together, the
 * queue orders half-edges by the smallest key of their list, and windows are filtered against
 * vertex distances instead of being intersected with each other.
 *
 * A window lives on a half-edge h and propagates into h's face. In h's frame (tail at the origin,
 * head at (len,0), opposite vertex C at (cx,cy), cy>0) the window is the interval [b0,b1] of the
 * x-axis lit by a (pseudo-)source at (sx,sy), sy<=0, carrying distance sigma: the distance at x is
 * sigma + |(x,0)-(sx,sy)|.
 *
 * Queue keys never decrease (a child's key is at least its parent's), so when a vertex event pops
 * its estimate is final (target queries with A* keys: see run_core); saddle / boundary vertices then emit windows as pseudo-sources, only into
 * the wedge where a shortest path through them can continue (angle >= pi on both sides of the
 * arrival direction). Rules that remove windows, all exact:
 *  - vertex pruning (VTP): every vertex estimate d(v) is the length of a real surface path, so any
 *    part of a window where d(v) + |v p| < window distance at p — v one of the four vertices of the
 *    two faces beside the edge, where the segment v–p stays in a face — cannot carry a shortest
 *    path. Against the edge's endpoints the dominated part is a prefix / suffix in closed form;
 *    against the two off-edge vertices the whole window goes when both ends are dominated (the
 *    region {d_w > d(v) + |v p|} is convex when d(v) >= sigma);
 *  - one split per corner (VTP rule 1): see propagate().
 * Tolerances only ever keep more windows (1e-12 of the bounding-box diagonal). */
#include "geodesic/vtp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  double b0, b1, sx, sy, sigma;
  int he;
  int next; /* next queued window on the same half-edge, -1 at the end */
} vwin;

typedef struct {
  double key;
  int id; /* >= 0 half-edge with queued windows, < 0 vertex event -(v+1) */
} hent;

enum { VS_SETTLED = 1, VS_TARGET = 2, VS_SOURCE = 4, VS_TOUCHED = 8 };

struct ssi_vtp_ws {
  int nv;
  unsigned char *vs;
  int *arr_he;     /* arrival of the current estimate: corner half-edge (tail = vertex), -1 unknown */
  double *arr_y, *arr_x; /* and direction inside that corner (y, x: atan2 taken only on emission) */
  vwin *pool;
  int npool, cappool;
  int *freeids;
  int nfree;
  hent *heap;
  size_t hsize, hcap;
  int *hpos; /* nh + nv: heap position of each half-edge / vertex entry, -1 when absent */
  ssi_vtp_stats st;
  int nomem;
  /* per half-edge: the best path to the opposite vertex found so far whose last segment crosses the
   * face from the edge (distance, crossing abscissa); valid when stamp == run */
  double *bestd, *bestx;
  int *head;     /* queued windows of each half-edge (list) */
  double *hkey;  /* smallest key among them, INFINITY when none */
  unsigned *hgen; /* A*: target-set generation hkey was computed with */
  unsigned *stamp;
  unsigned run;
  int nh;
  /* run-time context */
  const ss_geodesic_mesh *gm;
  double *d;
  double tol, maxd;
  /* Per-vertex state lives in the workspace and is reset through the list of vertices a run
   * touched, so a local query costs what it settles, not O(nv). Untouched: d = INFINITY,
   * arr_he = -1, vs = 0, vkey = emitted = INFINITY. */
  double *dd;      /* nv distance estimates (ws->d points here) */
  double *vkey;    /* A*: key of the vertex's latest queued event */
  unsigned *vgen;  /* A*: target-set generation of vkey */
  unsigned tgen;   /* A*: bumped when a target is final and leaves the bound's target set */
  double *emitted; /* A*: sigma of the vertex's latest emission as a pseudo-source */
  int *touched, ntouched;
  /* A* (target queries): keys add a lower bound on the remaining length to the nearest remaining
   * target (Euclidean, landmarks); keys are then no longer monotone (see run_core) */
  int astar, nht, nlm;
  double ht[3 * SS_VTP_MAX_HEUR];
  double lt[SS_VTP_MAX_HEUR * SS_GEODESIC_MAX_LANDMARKS]; /* landmark distances of the targets */
  int hv[SS_VTP_MAX_HEUR];                                /* the targets themselves */
  const double *lmf;                                      /* the mesh's landmark fields, this run */
};

ssi_vtp_ws *ssi_vtp_ws_new(int nv, int nf) {
  ssi_vtp_ws *ws = calloc(1, sizeof *ws);
  if (!ws) return NULL;
  ws->nv = nv;
  ws->nh = 3 * nf;
  size_t nh = (size_t)(nf > 0 ? 3 * (size_t)nf : 1);
  ws->bestd = malloc(sizeof(double) * nh);
  ws->bestx = malloc(sizeof(double) * nh);
  ws->stamp = calloc(nh, sizeof(unsigned));
  ws->head = malloc(sizeof(int) * nh);
  ws->hkey = malloc(sizeof(double) * nh);
  ws->hgen = malloc(sizeof(unsigned) * nh);
  ws->vs = calloc((size_t)(nv > 0 ? nv : 1), 1);
  ws->arr_he = malloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
  ws->arr_y = malloc(sizeof(double) * (size_t)(nv > 0 ? nv : 1));
  ws->arr_x = malloc(sizeof(double) * (size_t)(nv > 0 ? nv : 1));
  size_t nvv = (size_t)(nv > 0 ? nv : 1);
  ws->dd = malloc(sizeof(double) * nvv);
  ws->vkey = malloc(sizeof(double) * nvv);
  ws->vgen = calloc(nvv, sizeof(unsigned));
  ws->emitted = malloc(sizeof(double) * nvv);
  ws->touched = malloc(sizeof(int) * nvv);
  ws->cappool = 1024;
  ws->pool = malloc(sizeof(vwin) * (size_t)ws->cappool);
  ws->freeids = malloc(sizeof(int) * (size_t)ws->cappool);
  ws->hcap = 1024;
  ws->heap = malloc(sizeof(hent) * ws->hcap);
  ws->hpos = malloc(sizeof(int) * (nh + nvv));
  if (ws->hpos)
    for (size_t i = 0; i < nh + nvv; i++) ws->hpos[i] = -1;
  if (!ws->head || !ws->hkey || !ws->hgen || !ws->vgen || !ws->arr_he || !ws->arr_y || !ws->arr_x || !ws->bestd || !ws->bestx || !ws->stamp || !ws->vs || !ws->pool || !ws->freeids || !ws->heap ||
      !ws->hpos || !ws->dd || !ws->vkey || !ws->emitted || !ws->touched) {
    ssi_vtp_ws_free(ws);
    return NULL;
  }
  for (int i = 0; i < nv; i++) { ws->dd[i] = INFINITY; ws->vkey[i] = INFINITY; ws->emitted[i] = INFINITY; ws->arr_he[i] = -1; }
  ws->d = ws->dd;
  return ws;
}

void ssi_vtp_ws_free(ssi_vtp_ws *ws) {
  if (!ws) return;
  free(ws->bestd); free(ws->bestx); free(ws->stamp); free(ws->head); free(ws->hkey); free(ws->hgen); free(ws->vgen);
  free(ws->arr_he); free(ws->arr_y); free(ws->arr_x);
  free(ws->dd); free(ws->vkey); free(ws->emitted); free(ws->touched);
  free(ws->vs); free(ws->pool); free(ws->freeids); free(ws->heap); free(ws->hpos);
  free(ws);
}

void ssi_vtp_ws_stats(const ssi_vtp_ws *ws, ssi_vtp_stats *st) { *st = ws->st; }

/* ---- indexed 4-ary heap (shallower than a binary heap: fewer unpredictable branches per pop) --
 * One entry per half-edge / vertex at most, keyed by its current key: a lower key moves the entry
 * up instead of queueing a second one, so no stale entries are popped (half of all pops before). */
static inline int hslot(const ssi_vtp_ws *ws, int id) { return id >= 0 ? id : ws->nh - id - 1; }

static inline void heap_place(ssi_vtp_ws *ws, size_t i, hent e) {
  ws->heap[i] = e;
  ws->hpos[hslot(ws, e.id)] = (int)i;
}

static void heap_sift_down(ssi_vtp_ws *ws, size_t i, hent e) {
  hent *h = ws->heap;
  size_t n = ws->hsize;
  for (;;) {
    size_t c = 4 * i + 1;
    if (c >= n) break;
    size_t best = c;
    double bk = h[c].key;
    size_t end = c + 4 < n ? c + 4 : n;
    for (size_t j = c + 1; j < end; j++)
      if (h[j].key < bk) { bk = h[j].key; best = j; }
    if (bk >= e.key) break;
    heap_place(ws, i, h[best]);
    i = best;
  }
  heap_place(ws, i, e);
}

/* Insert id with `key`, or move its entry to `key`. */
static int heap_push(ssi_vtp_ws *ws, double key, int id) {
  int p = ws->hpos[hslot(ws, id)];
  hent e = {key, id};
  size_t i;
  if (p >= 0) {
    if (key > ws->heap[p].key) { heap_sift_down(ws, (size_t)p, e); return 0; }
    i = (size_t)p;
  } else {
    if (ws->hsize == ws->hcap) {
      size_t nc = ws->hcap * 2;
      hent *nh = realloc(ws->heap, sizeof(hent) * nc);
      if (!nh) { ws->nomem = 1; return -1; }
      ws->heap = nh; ws->hcap = nc;
    }
    i = ws->hsize++;
    if (ws->hsize > ws->st.peak_heap) ws->st.peak_heap = ws->hsize;
  }
  hent *h = ws->heap;
  while (i > 0) {
    size_t q = (i - 1) >> 2;
    if (h[q].key <= key) break;
    heap_place(ws, i, h[q]);
    i = q;
  }
  heap_place(ws, i, e);
  return 0;
}

static hent heap_pop(ssi_vtp_ws *ws) {
  hent top = ws->heap[0], last = ws->heap[--ws->hsize];
  ws->hpos[hslot(ws, top.id)] = -1;
  if (ws->hsize > 0) heap_sift_down(ws, 0, last);
  return top;
}

/* Entries left by an early stop leave the index clean for the next run. */
static void heap_clear(ssi_vtp_ws *ws) {
  for (size_t i = 0; i < ws->hsize; i++) ws->hpos[hslot(ws, ws->heap[i].id)] = -1;
  ws->hsize = 0;
}

/* ---- window pool -------------------------------------------------------------------------- */
static int win_alloc(ssi_vtp_ws *ws) {
  if (ws->nfree > 0) return ws->freeids[--ws->nfree];
  if (ws->npool == ws->cappool) {
    int nc = ws->cappool * 2;
    vwin *np = realloc(ws->pool, sizeof(vwin) * (size_t)nc);
    if (!np) { ws->nomem = 1; return -1; }
    ws->pool = np;
    int *nf = realloc(ws->freeids, sizeof(int) * (size_t)nc);
    if (!nf) { ws->nomem = 1; return -1; }
    ws->freeids = nf;
    ws->cappool = nc;
  }
  int id = ws->npool++;
  if ((size_t)ws->npool > ws->st.peak_windows) ws->st.peak_windows = (size_t)ws->npool;
  return id;
}

/* ---- touched vertices and A* bounds ------------------------------------------------------- */
static inline void v_touch(ssi_vtp_ws *ws, int v) {
  if (!(ws->vs[v] & VS_TOUCHED)) { ws->vs[v] |= VS_TOUCHED; ws->touched[ws->ntouched++] = v; }
}

static void ws_reset(ssi_vtp_ws *ws) {
  for (int k = 0; k < ws->ntouched; k++) {
    int v = ws->touched[k];
    ws->dd[v] = INFINITY; ws->vkey[v] = INFINITY; ws->emitted[v] = INFINITY; ws->arr_he[v] = -1; ws->vs[v] = 0;
  }
  ws->ntouched = 0;
}

/* Lower bounds on the remaining length to the nearest target: the Euclidean distance (surface
 * paths are 3D curves) and, when the mesh carries landmark fields, |d_L(p) - d_L(t)| (triangle
 * inequality). Lowered by a relative 1e-12 and the tolerance so that round-off never lifts a bound
 * above the true remaining length. */
static inline double heur_safe(const ssi_vtp_ws *ws, double b) {
  b = b * (1 - 1e-12) - ws->tol;
  return b > 0 ? b : 0;
}

static inline double heur_pt(const ssi_vtp_ws *ws, int v) {
  if (!ws->astar) return 0;
  const double *p = ws->gm->V + 3 * (size_t)v;
  const double *lv = ws->nlm ? ws->lmf + (size_t)v * ws->nlm : NULL;
  double best = INFINITY;
  for (int j = 0; j < ws->nht; j++) {
    const double *t = ws->ht + 3 * j;
    double dx = p[0] - t[0], dy = p[1] - t[1], dz = p[2] - t[2], b = sqrt(dx * dx + dy * dy + dz * dz);
    const double *lt = ws->lt + j * ws->nlm;
    for (int k = 0; k < ws->nlm; k++) {
      double q = fabs(lv[k] - lt[k]);
      if (q > b && q < INFINITY) b = q; /* NaN / inf (unreachable landmark): skipped */
    }
    if (b < best) best = b;
  }
  return heur_safe(ws, best);
}

/* Same for the piece [b0,b1] of half-edge h: the nearest point of the piece to the target, and
 * landmark distances along the edge bracketed by the 1-Lipschitz bounds from its end vertices. */
static inline double heur_seg(const ssi_vtp_ws *ws, int h, double b0, double b1) {
  if (!ws->astar) return 0;
  const ss_geodesic_mesh *gm = ws->gm;
  int ia = gm->F[h], ib = gm->F[ssi_he_next(h)];
  const double *a = gm->V + 3 * (size_t)ia, *b = gm->V + 3 * (size_t)ib;
  double L = gm->fr[h].len, inv = 1.0 / L;
  double u[3] = {(b[0] - a[0]) * inv, (b[1] - a[1]) * inv, (b[2] - a[2]) * inv};
  double lo[SS_GEODESIC_MAX_LANDMARKS], hi[SS_GEODESIC_MAX_LANDMARKS];
  int K = ws->nlm;
  if (K) {
    const double *la = ws->lmf + (size_t)ia * K, *lb = ws->lmf + (size_t)ib * K;
    for (int k = 0; k < K; k++) {
      /* d_L(x) >= max(la - x, lb - (L - x)), <= min(la + x, lb + L - x) on the edge */
      double xl = 0.5 * (la[k] - lb[k] + L), xh = 0.5 * (lb[k] + L - la[k]);
      xl = xl < b0 ? b0 : (xl > b1 ? b1 : xl);
      xh = xh < b0 ? b0 : (xh > b1 ? b1 : xh);
      double l1 = la[k] - xl, l2 = lb[k] - (L - xl), h1 = la[k] + xh, h2 = lb[k] + (L - xh);
      lo[k] = l1 > l2 ? l1 : l2;
      hi[k] = h1 < h2 ? h1 : h2;
    }
  }
  double best = INFINITY;
  for (int j = 0; j < ws->nht; j++) {
    const double *t = ws->ht + 3 * j;
    double w[3] = {t[0] - a[0], t[1] - a[1], t[2] - a[2]};
    double x = w[0] * u[0] + w[1] * u[1] + w[2] * u[2];
    x = x < b0 ? b0 : (x > b1 ? b1 : x);
    double dx = w[0] - x * u[0], dy = w[1] - x * u[1], dz = w[2] - x * u[2];
    double bnd = sqrt(dx * dx + dy * dy + dz * dz);
    const double *lt = ws->lt + j * K;
    for (int k = 0; k < K; k++) {
      double q1 = lo[k] - lt[k], q2 = lt[k] - hi[k], q = q1 > q2 ? q1 : q2;
      if (q > bnd && q < INFINITY) bnd = q;
    }
    if (bnd < best) best = bnd;
  }
  return heur_safe(ws, best);
}

/* ---- vertices ----------------------------------------------------------------------------- */
/* New estimate `val` for v through a path arriving inside corner hc along direction (dx,dy) in that
 * corner's frame (hc = -1: the
 * path bends on the way, direction not recorded). Pseudo-source vertices keep the arrival direction
 * of a straight arrival, also on a tie, so that they emit only where a geodesic can continue. */
static void vertex_update(ssi_vtp_ws *ws, int v, double val, int hc, double dy, double dx) {
  if (!ws->astar && (ws->vs[v] & VS_SETTLED)) return;
  if (!(val < ws->d[v])) {
    if (hc >= 0 && ws->arr_he[v] < 0 && val <= ws->d[v] + ws->tol) { ws->arr_he[v] = hc; ws->arr_y[v] = dy; ws->arr_x[v] = dx; }
    return;
  }
  v_touch(ws, v);
  ws->d[v] = val;
  ws->arr_he[v] = hc; ws->arr_y[v] = dy; ws->arr_x[v] = dx;
  if ((ws->gm->vflag[v] & SS_GV_PSEUDO) || (ws->vs[v] & VS_TARGET)) {
    double key = val + heur_pt(ws, v);
    ws->vkey[v] = key;
    ws->vgen[v] = ws->tgen;
    heap_push(ws, key, -(v + 1));
  }
}

static inline void he_touch(ssi_vtp_ws *ws, int h) {
  if (ws->stamp[h] != ws->run) {
    ws->stamp[h] = ws->run;
    ws->bestd[h] = INFINITY;
    ws->head[h] = -1;
    ws->hkey[h] = INFINITY;
    ws->hgen[h] = ws->tgen;
  }
}

/* ---- pruning ------------------------------------------------------------------------------ */
/* Cut from [*b0,*b1] the parts dominated by the vertices of the two faces beside half-edge h.
 * Returns 0 when nothing is left. */
static int prune(const ssi_vtp_ws *ws, int h, double *pb0, double *pb1, double sx, double sy, double sigma) {
  const ss_geodesic_mesh *gm = ws->gm;
  const double *d = ws->d, tol = ws->tol;
  const ssi_he_frame *fr = gm->fr + h;
  double L = fr->len, b0 = *pb0, b1 = *pb1;
  double sy2 = sy * sy;
  /* tail A at x = 0: h_A(x) = sigma + |s - x| - d(A) - x is non-increasing in x */
  double dA = d[gm->F[h]];
  if (dA < INFINITY) {
    double a = dA + tol - sigma;
    /* |s - x| > x + a, without the square root */
    double q0 = b0 + a;
    if (q0 < 0 || (b0 - sx) * (b0 - sx) + sy2 > q0 * q0) {
      double q1 = b1 + a;
      if (q1 < 0 || (b1 - sx) * (b1 - sx) + sy2 > q1 * q1) return 0;
      double den = 2 * (a + sx);
      if (den > 0) {
        double x = (sx * sx + sy2 - a * a) / den;
        if (x > b0) b0 = x < b1 ? x : b1;
      }
    }
  }
  /* head B at x = L: mirror image */
  double dB = d[gm->F[ssi_he_next(h)]];
  if (dB < INFINITY) {
    double a = dB + tol - sigma, tx = L - sx;
    double q1 = L - b1 + a;
    if (q1 < 0 || (b1 - sx) * (b1 - sx) + sy2 > q1 * q1) {
      double q0 = L - b0 + a;
      if (q0 < 0 || (b0 - sx) * (b0 - sx) + sy2 > q0 * q0) return 0;
      double den = 2 * (a + tx);
      if (den > 0) {
        double x = L - (tx * tx + sy2 - a * a) / den;
        if (x < b1) b1 = x > b0 ? x : b0;
      }
    }
  }
  if (!(b1 - b0 > 1e-12 * L)) return 0;
  /* off-edge vertices: C in this face, P in the face the window came through */
  double dC = d[gm->F[ssi_he_prev(h)]];
  if (dC < INFINITY && dC >= sigma) {
    double px = fr->cx, py = fr->cy;
    double t0 = sigma + sqrt((b0 - sx) * (b0 - sx) + sy2) - dC - sqrt((b0 - px) * (b0 - px) + py * py);
    if (t0 > tol) {
      double t1 = sigma + sqrt((b1 - sx) * (b1 - sx) + sy2) - dC - sqrt((b1 - px) * (b1 - px) + py * py);
      if (t1 > tol) return 0;
    }
  }
  int t = gm->twin[h];
  if (t >= 0) {
    double dP = d[gm->F[ssi_he_prev(t)]];
    if (dP < INFINITY && dP >= sigma) {
      double px = L - gm->fr[t].cx, py = -gm->fr[t].cy;
      double t0 = sigma + sqrt((b0 - sx) * (b0 - sx) + sy2) - dP - sqrt((b0 - px) * (b0 - px) + py * py);
      if (t0 > tol) {
        double t1 = sigma + sqrt((b1 - sx) * (b1 - sx) + sy2) - dP - sqrt((b1 - px) * (b1 - px) + py * py);
        if (t1 > tol) return 0;
      }
    }
  }
  *pb0 = b0; *pb1 = b1;
  return 1;
}

static double win_key(double b0, double b1, double sx, double sy, double sigma) {
  double xm = sx < b0 ? b0 : (sx > b1 ? b1 : sx);
  return sigma + sqrt((xm - sx) * (xm - sx) + sy * sy);
}

static void add_window(ssi_vtp_ws *ws, int h, double b0, double b1, double sx, double sy, double sigma) {
  if (sy > 0) sy = 0; /* round-off: the source is never on the face's side */
  if (!prune(ws, h, &b0, &b1, sx, sy, sigma)) return;
  double key = win_key(b0, b1, sx, sy, sigma);
  if (key > ws->maxd) return;
  if (ws->astar) key += heur_seg(ws, h, b0, b1);
  int id = win_alloc(ws);
  if (id < 0) return;
  vwin *w = ws->pool + id;
  w->b0 = b0; w->b1 = b1; w->sx = sx; w->sy = sy; w->sigma = sigma; w->he = h;
  ws->st.windows_created++;
  /* VTP-style grouping: the windows of a half-edge wait in a list and cross its face together;
   * the queue holds the half-edge under the smallest key of its list */
  he_touch(ws, h);
  w->next = ws->head[h];
  ws->head[h] = id;
  if (key < ws->hkey[h]) {
    /* an older-generation hkey stays marked old: the minimum is still a valid (weaker) bound */
    if (ws->hkey[h] == INFINITY) ws->hgen[h] = ws->tgen;
    ws->hkey[h] = key;
    heap_push(ws, key, h);
  }
}

/* ---- pseudo-source ------------------------------------------------------------------------ */
/* Where the ray from the corner's tail at local angle phi meets the opposite side a->b, as a
 * fraction from a. */
static double corner_hit(const ssi_he_frame *fh, double phi) {
  double ux = cos(phi), uy = sin(phi);
  double ex = fh->cx - fh->len, ey = fh->cy;
  double den = ux * ey - uy * ex;
  double t = den != 0 ? fh->len * uy / den : 0;
  return t > 0 ? (t < 1 ? t : 1) : 0;
}

/* Windows from v over local angles [p0,p1] of corner h (v->a, face v,a,b). */
static void emit_corner(ssi_vtp_ws *ws, int h, double p0, double p1, double sigma) {
  const ss_geodesic_mesh *gm = ws->gm;
  const ssi_he_frame *fh = gm->fr + h;
  int ho = ssi_he_next(h), hp = ssi_he_prev(h);
  double ang = gm->ang[h];
  if (p0 <= 0) vertex_update(ws, gm->F[ho], sigma + fh->len, ho, gm->fr[ho].cy, gm->fr[ho].cx);
  if (p1 >= ang) vertex_update(ws, gm->F[hp], sigma + gm->fr[hp].len, hp, 0, 1);
  int t = gm->twin[ho];
  if (t < 0) return;
  const ssi_he_frame *fo = gm->fr + ho;
  double L = fo->len;
  double t0 = p0 <= 0 ? 0 : corner_hit(fh, p0), t1 = p1 >= ang ? 1 : corner_hit(fh, p1);
  if (t1 > t0) add_window(ws, t, (1 - t1) * L, (1 - t0) * L, L - fo->cx, -fo->cy, sigma);
}

static void emit(ssi_vtp_ws *ws, int v) {
  const ss_geodesic_mesh *gm = ws->gm;
  double sigma = ws->d[v];
  int hin = ws->arr_he[v];
  if ((ws->vs[v] & VS_SOURCE) || (gm->vflag[v] & SS_GV_FULL) || hin < 0) {
    for (int k = gm->vptr[v]; k < gm->vptr[v + 1]; k++) emit_corner(ws, gm->vcorner[k], 0, M_PI, sigma);
    return;
  }
  /* A shortest path through a vertex leaves it at an angle >= pi on both sides of its arrival
   * direction: only the wedge [in + pi, in + theta - pi] (widened by a hair) can need windows. */
  const double margin = 1e-7;
  double theta = gm->theta[v], ain = gm->cang[hin] + atan2(ws->arr_y[v], ws->arr_x[v]);
  double w0 = ain + M_PI - margin, w1 = ain + theta - M_PI + margin;
  for (int k = gm->vptr[v]; k < gm->vptr[v + 1]; k++) {
    int h = gm->vcorner[k];
    double c0 = gm->cang[h], ang = gm->ang[h];
    for (int r = -1; r <= 1; r++) {
      double lo = w0 + r * theta - c0, hi = w1 + r * theta - c0;
      if (lo < 0) lo = 0;
      if (hi > ang) hi = ang;
      if (hi >= lo) emit_corner(ws, h, lo, hi, sigma);
    }
  }
}

/* ---- propagation through a face ----------------------------------------------------------- */
static inline double clamp01(double x) { return x > 0 ? (x < 1 ? x : 1) : 0; } /* NaN -> 0 */

static void propagate(ssi_vtp_ws *ws, const vwin *w) {
  const ss_geodesic_mesh *gm = ws->gm;
  int h = w->he, h1 = ssi_he_next(h), h2 = ssi_he_prev(h);
  const ssi_he_frame *fr = gm->fr + h;
  double L = fr->len, cx = fr->cx, cy = fr->cy;
  double sx = w->sx, sy = w->sy, sigma = w->sigma, b0 = w->b0, b1 = w->b1;
  double xC = sx + (cx - sx) * (-sy) / (cy - sy); /* where the ray through C crosses the edge */
  /* this window's shortest path to C: straight when C is lit, else bending at the nearer end */
  double xw, Dw;
  if (xC < b0) {
    xw = b0;
    Dw = sigma + sqrt((b0 - sx) * (b0 - sx) + sy * sy) + sqrt((cx - b0) * (cx - b0) + cy * cy);
  } else if (xC > b1) {
    xw = b1;
    Dw = sigma + sqrt((b1 - sx) * (b1 - sx) + sy * sy) + sqrt((cx - b1) * (cx - b1) + cy * cy);
  } else {
    xw = xC;
    Dw = sigma + sqrt((cx - sx) * (cx - sx) + (cy - sy) * (cy - sy));
  }
  {
    /* arrival direction at C inside its corner (C->A, then towards B) */
    double vx = (xC < b0 || xC > b1) ? xw - cx : sx - cx, vy = (xC < b0 || xC > b1) ? -cy : sy - cy;
    int straight = !(xC < b0 || xC > b1) && (gm->vflag[gm->F[h2]] & SS_GV_PSEUDO);
    vertex_update(ws, gm->F[h2], Dw, straight ? h2 : -1, -cx * vy + cy * vx, -cx * vx - cy * vy);
  }
  /* one split per corner (VTP rule 1): if an earlier window reached C more cheaply through the
   * segment (x*,0)-C, rays of this window from the left of x* to edge B-C cross that segment and are
   * beaten there, and likewise on the other side; so left children stop at x*, right ones start at x*. */
  double cutAC = b1, cutBC = b0;
  he_touch(ws, h);
  if (Dw < ws->bestd[h]) {
    ws->bestd[h] = Dw; ws->bestx[h] = xw;
  } else if (Dw > ws->bestd[h] + ws->tol) {
    cutAC = ws->bestx[h]; cutBC = ws->bestx[h];
  }
  int t1 = gm->twin[h1], t2 = gm->twin[h2];
  double lAC = gm->fr[h2].len, lBC = gm->fr[h1].len;
  /* A-C child: rays through [b0, e1] */
  double e1 = xC < b1 ? xC : b1;
  if (cutAC < e1) e1 = cutAC;
  if (t2 >= 0 && e1 > b0) {
    /* child frame: origin A, x toward C (twin of C->A); fraction along A->C where the ray through
     * (b,0) meets it */
    double f0 = clamp01(sy * b0 / (cx * sy + cy * (b0 - sx)));
    double f1 = e1 >= xC ? 1.0 : clamp01(sy * e1 / (cx * sy + cy * (e1 - sx)));
    double inv = 1.0 / lAC;
    double nsx = (sx * cx + sy * cy) * inv, nsy = (cx * sy - cy * sx) * inv;
    if (f1 > f0) add_window(ws, t2, f0 * lAC, f1 * lAC, nsx, nsy, sigma);
  }
  /* B-C child: rays through [e0, b1] */
  double e0 = xC > b0 ? xC : b0;
  if (cutBC > e0) e0 = cutBC;
  if (t1 >= 0 && b1 > e0) {
    /* child frame: origin C, x toward B (twin of B->C). Its direction is taken from the angle at
     * B (frame of B->C, built from exact coordinate differences), not from (L - cx, -cy): when B-C
     * is tiny against A-B that difference cancels and the rotation error would be multiplied by
     * the distance to the source (seen on needle triangles). */
    const ssi_he_frame *f1 = gm->fr + h1;
    double cb = f1->cx / L, sb = f1->cy / L;        /* cos, sin of the angle at B */
    double ex = lBC * cb, ey = -lBC * sb;            /* B - C */
    double qx = sx - L + lBC * cb, qy = sy - lBC * sb; /* s - C */
    double g0, g1;
    if (e0 <= xC) g0 = 0;
    else {
      double dx = e0 - sx, dy = -sy;
      g0 = clamp01((qx * dy - qy * dx) / (ex * dy - ey * dx));
    }
    {
      double dx = b1 - sx, dy = -sy;
      g1 = clamp01((qx * dy - qy * dx) / (ex * dy - ey * dx));
    }
    double ux = cb, uy = -sb;
    double nsx = qx * ux + qy * uy, nsy = ux * qy - uy * qx;
    if (g1 > g0) add_window(ws, t1, g0 * lBC, g1 * lBC, nsx, nsy, sigma);
  }
}

/* ---- driver ------------------------------------------------------------------------------- */
/* Early stop on targets. Without A* keys never decrease (a child's key is at least its parent's),
 * so a vertex is final when its event pops, as in Dijkstra. With A* a key is a lower bound on the
 * length of any source-target path continuing through the entry (window: smallest window
 * distance + Euclidean distance from the window's piece of edge to the nearest target; vertex:
 * estimate + Euclidean distance). Every rule that removes windows only removes parts that are
 * strictly longer than some real path (vertex estimates are always lengths of real paths), whatever
 * the processing order, so the windows along a shortest path are all created; the first of them not
 * yet processed is queued with a key <= the true distance. Hence when a target's current event pops,
 * every queued key is >= its estimate and the estimate is exact. Vertex estimates may still drop
 * after a pseudo-source vertex emitted, so it emits again when they do (A* only). */
static ss_status run_core(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm, ssi_vtp_ws *ws,
                          const int *sources, int nsources,
                          double max_dist, const int *targets, int ntargets, int astar, int first,
                          double *settled_radius, int *first_hit, ss_error *err) {
  if (!gm || !ws || ws->nv != gm->nv || ws->nh != 3 * gm->nf) return ss_fail(err, SS_ERR_INVALID, "invalid geodesic workspace");
  if (nsources < 1 || !sources) return ss_fail(err, SS_ERR_INVALID, "no source vertex given");
  int nv = gm->nv;
  for (int i = 0; i < nsources; i++)
    if (sources[i] < 0 || sources[i] >= nv)
      return ss_fail(err, SS_ERR_INVALID, "source vertex %d outside [0,%d)", sources[i], nv);
  for (int i = 0; i < ntargets; i++)
    if (!targets || targets[i] < 0 || targets[i] >= nv)
      return ss_fail(err, SS_ERR_INVALID, "target vertex %d outside [0,%d)", targets ? targets[i] : -1, nv);
  ws_reset(ws);
  memset(&ws->st, 0, sizeof ws->st);
  heap_clear(ws);
  ws->npool = 0; ws->nfree = 0; ws->nomem = 0;
  ws->gm = gm; ws->d = ws->dd;
  if (++ws->run == 0) { /* stamp wrap-around: clear once every 2^32 runs */
    memset(ws->stamp, 0, sizeof(unsigned) * (size_t)(ws->nh > 0 ? ws->nh : 1));
    ws->run = 1;
  }
  ws->tol = 1e-12 * gm->scale;
  ws->maxd = (max_dist > 0 && !isnan(max_dist)) ? max_dist : INFINITY;
  ws->astar = astar && ntargets > 0 && ntargets <= SS_VTP_MAX_HEUR;
  ws->nht = 0;
  if (ws->astar) {
    ws->maxd = INFINITY;
    const double *lmf = lm && lm->nv == nv ? lm->lm : NULL;
    ws->lmf = lmf;
    ws->nlm = lmf ? lm->nlm : 0;
    for (int i = 0; i < ntargets; i++) {
      int dup = 0;
      for (int j = 0; j < ws->nht; j++) dup |= ws->hv[j] == targets[i];
      if (dup) continue;
      ws->hv[ws->nht] = targets[i];
      memcpy(ws->ht + 3 * ws->nht, gm->V + 3 * (size_t)targets[i], 3 * sizeof(double));
      for (int k = 0; k < ws->nlm; k++) ws->lt[ws->nht * ws->nlm + k] = lmf[(size_t)targets[i] * ws->nlm + k];
      ws->nht++;
    }
  }
  int left = 0;
  for (int i = 0; i < ntargets; i++)
    if (!(ws->vs[targets[i]] & VS_TARGET)) { v_touch(ws, targets[i]); ws->vs[targets[i]] |= VS_TARGET; left++; }
  for (int i = 0; i < nsources; i++) {
    int s = sources[i];
    if (ws->vs[s] & VS_SOURCE) continue;
    v_touch(ws, s);
    ws->vs[s] |= VS_SOURCE;
    ws->d[s] = 0;
    ws->vkey[s] = heur_pt(ws, s);
    ws->vgen[s] = ws->tgen;
    heap_push(ws, ws->vkey[s], -(s + 1));
  }
  double radius = INFINITY;
  int stop_targets = ntargets > 0, hit_dummy;
  if (!first_hit) first_hit = &hit_dummy;
  *first_hit = -1;
  /* Bounded cost. On clean meshes a full field creates 4-8 windows per half-edge. Around the apex of
   * a cone of sliver triangles (an octahedron with one vertex pulled out to 1e9) a window wraps
   * around and comes back to the same edges ever closer to the apex, and the distances of successive
   * wraps differ by less than one ulp, so no pruning rule can tell them apart: the spiral never
   * ends. Past 1e6 + 16 nh^1.5 windows (1e6 on tiny meshes, 1.4e8 on FAUST, which needs 2e5) the
   * propagation gives up with a message naming a face where it was still going. */
  const double nhd = (double)ws->nh;
  const long long wcap = (long long)(1e6 + 16.0 * nhd * sqrt(nhd));
  int runaway_face = -1;
  while (ws->hsize > 0 && !ws->nomem) {
    hent e = heap_pop(ws);
    if (e.key > ws->maxd) { radius = ws->maxd; break; }
    ws->st.events++;
    if (e.id < 0) {
      int v = -e.id - 1;
      if (ws->astar) {
        if (e.key != ws->vkey[v]) continue; /* superseded by a better estimate */
        if (ws->vgen[v] != ws->tgen) {         /* bound computed for a larger target set: tighten */
          ws->vkey[v] = ws->d[v] + heur_pt(ws, v);
          ws->vgen[v] = ws->tgen;
          heap_push(ws, ws->vkey[v], e.id);
          continue;
        }
        ws->vkey[v] = -1;                     /* consumed */
        if ((ws->vs[v] & VS_TARGET) && !(ws->vs[v] & VS_SETTLED)) {
          ws->vs[v] |= VS_SETTLED;
          if (--left == 0 || first) { radius = e.key; *first_hit = v; break; }
          /* v is final: later keys only need to bound the paths to the remaining targets */
          for (int j = 0; j < ws->nht; j++)
            if (ws->hv[j] == v) {
              int last = --ws->nht;
              ws->hv[j] = ws->hv[last];
              memcpy(ws->ht + 3 * j, ws->ht + 3 * last, 3 * sizeof(double));
              memcpy(ws->lt + j * ws->nlm, ws->lt + last * ws->nlm, (size_t)ws->nlm * sizeof(double));
              ws->tgen++;
              break;
            }
        }
        if (((gm->vflag[v] & SS_GV_PSEUDO) || (ws->vs[v] & VS_SOURCE)) && ws->d[v] < ws->emitted[v]) {
          ws->emitted[v] = ws->d[v];
          emit(ws, v);
        }
        continue;
      }
      if (ws->vs[v] & VS_SETTLED) continue;
      ws->vs[v] |= VS_SETTLED;
      if (ws->vs[v] & VS_TARGET) {
        if ((--left == 0 || first) && stop_targets) { radius = e.key; *first_hit = v; break; }
      }
      if ((gm->vflag[v] & SS_GV_PSEUDO) || (ws->vs[v] & VS_SOURCE)) emit(ws, v);
      continue;
    }
    int h = e.id;
    if (ws->stamp[h] != ws->run || ws->head[h] < 0 || e.key != ws->hkey[h]) continue; /* stale */
    if (ws->astar && ws->hgen[h] != ws->tgen) { /* tighten a bound made for a larger target set */
      double k = INFINITY;
      for (int id = ws->head[h]; id >= 0; id = ws->pool[id].next) {
        const vwin *w = ws->pool + id;
        double kw = win_key(w->b0, w->b1, w->sx, w->sy, w->sigma) + heur_seg(ws, h, w->b0, w->b1);
        if (kw < k) k = kw;
      }
      ws->hkey[h] = k;
      ws->hgen[h] = ws->tgen;
      heap_push(ws, k, h);
      continue;
    }
    if (ws->st.windows_created > wcap) { runaway_face = h / 3; break; }
    int id = ws->head[h];
    ws->head[h] = -1;
    ws->hkey[h] = INFINITY;
    while (id >= 0) {
      vwin w = ws->pool[id];
      ws->freeids[ws->nfree++] = id;
      id = w.next;
      ws->st.windows_propagated++;
      propagate(ws, &w);
      if (ws->nomem) break;
    }
  }
  ws->st.touched = ws->ntouched;
  if (ws->nomem) return ss_fail(err, SS_ERR_NOMEM, "out of memory during geodesic propagation");
  if (runaway_face >= 0)
    return ss_fail(err, SS_ERR_NUMERIC,
                   "exact geodesics: the propagation did not finish after %lld windows on a mesh of %d faces (still "
                   "going around face %d): sliver (needle) triangles there make windows spiral; remesh the input "
                   "or use the graph method",
                   ws->st.windows_created, gm->nf, runaway_face);
  if (settled_radius) *settled_radius = radius;
  return SS_OK;
}

ss_status ssi_vtp_run(const ss_geodesic_mesh *gm, ssi_vtp_ws *ws, const int *sources, int nsources,
                     double max_dist, const int *targets, int ntargets, double *dist,
                     double *settled_radius, ss_error *err) {
  if (!dist) return ss_fail(err, SS_ERR_INVALID, "null distance output");
  ss_status st = run_core(gm, NULL, ws, sources, nsources, max_dist, targets, ntargets, 0, 0, settled_radius, NULL, err);
  if (st) return st;
  memcpy(dist, ws->dd, sizeof(double) * (size_t)gm->nv);
  if (ws->maxd < INFINITY)
    for (int i = 0; i < gm->nv; i++)
      if (dist[i] > ws->maxd) dist[i] = INFINITY;
  return SS_OK;
}

ss_status ssi_vtp_query(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm, ssi_vtp_ws *ws, int source,
                        const int *targets, int ntargets, int astar, int first, double *out, ss_error *err) {
  if (ntargets < 1 || !targets || !out) return ss_fail(err, SS_ERR_INVALID, "invalid target query");
  int hit = -1;
  ss_status st = run_core(gm, lm, ws, &source, 1, 0, targets, ntargets, astar, first, NULL, &hit, err);
  if (st) return st;
  if (first) {
    *out = hit >= 0 ? ws->dd[hit] : INFINITY; /* no hit: every target unreachable */
    return SS_OK;
  }
  for (int i = 0; i < ntargets; i++) out[i] = ws->dd[targets[i]];
  return SS_OK;
}
