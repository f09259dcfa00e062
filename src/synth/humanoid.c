/* Synthetic posable humanoid (metres, y up, facing +z, its left side on +x; ~1.75 m tall).
 *
 * Construction (deterministic, no randomness):
 *  1. Shape: an implicit surface, the smooth union (polynomial smooth-min) of ellipsoids (pelvis,
 *     abdomen, chest, head, palms, feet) and tapered capsules (neck, limbs, 3 finger stubs + a thumb
 *     per hand, 3 toe stubs per foot). The parts form a tree, so the surface is a sphere (genus 0).
 *  2. Rest-pose mesh: marching tetrahedra on a BCC lattice (closed manifold by construction), then
 *     Delaunay flips + CVT-like tangential relaxation projected back onto the implicit surface.
 *  3. Skeleton: 16 bones (pelvis root, abdomen, chest, head, upper arm/forearm/hand and
 *     thigh/shin/foot per side) with joints at the waist and lower chest (two spine joints), neck,
 *     shoulders, elbows, wrists, hips, knees and ankles. Each vertex takes the bone of its nearest
 *     part (the torso split by height into pelvis / abdomen / chest); those one-hot
 *     weights are diffused a few Jacobi steps on the mesh, so they blend only in a band of a few
 *     centimetres around each joint and are exactly rigid (0/1) elsewhere.
 *  4. Poses: forward kinematics of per-joint rotations, dual-quaternion skinning of the rest mesh.
 *     All poses share the rest connectivity and vertex order, so the ground-truth map is identity. */
#include "synth/synth_internal.h"
#include "specseg/synth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEG (M_PI / 180.0)

enum { P_CAPSULE, P_ELLIPSOID };
enum {
  B_PELVIS, B_ABDOMEN, B_CHEST, B_HEAD,
  B_UARM_L, B_FARM_L, B_HAND_L, B_UARM_R, B_FARM_R, B_HAND_R,
  B_THIGH_L, B_SHIN_L, B_FOOT_L, B_THIGH_R, B_SHIN_R, B_FOOT_R,
  NBONES,
  B_TORSO = -1 /* pelvis, abdomen or chest by height */
};

typedef struct {
  int type, bone;
  double k;            /* smooth-min radius used when merging this part into the union */
  double a[3], b[3];   /* capsule axis */
  double ra, rb;       /* capsule radii at a and b */
  double c[3], ax[9], r[3]; /* ellipsoid centre, unit axes (rows), radii */
  double bc[3], br, lbs;    /* bounding sphere; the part's value is >= (|x - bc| - br) * lbs */
} part;

#define MAXPARTS 48
typedef struct {
  part p[MAXPARTS];
  int n;
  double joint[NBONES][3];
  int parent[NBONES];
  double waist_y, chest_y; /* torso split: pelvis | abdomen | chest */
} body;

static void v_norm(double *v) {
  double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  v[0] /= l;
  v[1] /= l;
  v[2] /= l;
}
static void v_cross(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static void add_capsule(body *B, int bone, double k, const double *a, const double *b, double ra, double rb) {
  part *p = &B->p[B->n++];
  memset(p, 0, sizeof *p);
  p->type = P_CAPSULE;
  p->bone = bone;
  p->k = k;
  memcpy(p->a, a, sizeof p->a);
  memcpy(p->b, b, sizeof p->b);
  p->ra = ra;
  p->rb = rb;
  double h2 = 0;
  for (int d = 0; d < 3; d++) {
    p->bc[d] = 0.5 * (a[d] + b[d]);
    h2 += 0.25 * (b[d] - a[d]) * (b[d] - a[d]);
  }
  p->br = sqrt(h2) + (ra > rb ? ra : rb);
  p->lbs = 1;
}
/* Ellipsoid with axes u (radius r0), v (r1) and u x v (r2); u, v orthonormal. */
static void add_ellipsoid(body *B, int bone, double k, const double *c, const double *u, const double *v,
                          double r0, double r1, double r2) {
  part *p = &B->p[B->n++];
  memset(p, 0, sizeof *p);
  p->type = P_ELLIPSOID;
  p->bone = bone;
  p->k = k;
  memcpy(p->c, c, sizeof p->c);
  memcpy(p->ax, u, 3 * sizeof(double));
  memcpy(p->ax + 3, v, 3 * sizeof(double));
  v_cross(u, v, p->ax + 6);
  p->r[0] = r0;
  p->r[1] = r1;
  p->r[2] = r2;
  memcpy(p->bc, c, sizeof p->bc);
  p->br = fmax(r0, fmax(r1, r2));
  p->lbs = fmin(r0, fmin(r1, r2)) / p->br;
}

static double part_eval(const part *p, const double *x) {
  if (p->type == P_CAPSULE) {
    double v[3] = {p->b[0] - p->a[0], p->b[1] - p->a[1], p->b[2] - p->a[2]};
    double w[3] = {x[0] - p->a[0], x[1] - p->a[1], x[2] - p->a[2]};
    double t = (w[0] * v[0] + w[1] * v[1] + w[2] * v[2]) / (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double d[3] = {w[0] - t * v[0], w[1] - t * v[1], w[2] - t * v[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - (p->ra + t * (p->rb - p->ra));
  }
  double w[3] = {x[0] - p->c[0], x[1] - p->c[1], x[2] - p->c[2]}, s = 0;
  double rmin = p->r[0] < p->r[1] ? p->r[0] : p->r[1];
  if (p->r[2] < rmin) rmin = p->r[2];
  for (int j = 0; j < 3; j++) {
    double q = (w[0] * p->ax[3 * j] + w[1] * p->ax[3 * j + 1] + w[2] * p->ax[3 * j + 2]) / p->r[j];
    s += q * q;
  }
  /* not a true distance, but the right zero set and a gradient of about 1 near it */
  return (sqrt(s) - 1) * rmin;
}

static double smin(double a, double b, double k) {
  double h = k - fabs(a - b);
  if (h <= 0) return a < b ? a : b;
  h /= k;
  return (a < b ? a : b) - 0.25 * h * h * k;
}

/* Parts are merged one after the other; smin(f, g, k) = f whenever g >= f + k, so a part whose
 * bounding-sphere lower bound already says so is skipped: same value, far fewer evaluations. */
static double body_field(const double x[3], const void *ctx) {
  const body *B = ctx;
  double f = part_eval(&B->p[0], x);
  for (int i = 1; i < B->n; i++) {
    const part *p = &B->p[i];
    double d[3] = {x[0] - p->bc[0], x[1] - p->bc[1], x[2] - p->bc[2]};
    double lb = (sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - p->br) * p->lbs;
    if (lb >= f + p->k) continue;
    f = smin(f, part_eval(p, x), p->k);
  }
  return f;
}

static void set3(double *d, double x, double y, double z) {
  d[0] = x;
  d[1] = y;
  d[2] = z;
}
static void axpy3(double *out, const double *p, double s, const double *d) {
  for (int i = 0; i < 3; i++) out[i] = p[i] + s * d[i];
}
/* rotate unit vector u towards unit vector v (orthogonal to u) by angle a */
static void turn(double *out, const double *u, const double *v, double a) {
  for (int i = 0; i < 3; i++) out[i] = cos(a) * u[i] + sin(a) * v[i];
}

/* One side's arm and leg; s = +1 for the left (+x), -1 for the right. */
static void build_side(body *B, double s) {
  const int uarm = s > 0 ? B_UARM_L : B_UARM_R, farm = uarm + 1, hand = uarm + 2;
  const int thigh = s > 0 ? B_THIGH_L : B_THIGH_R, shin = thigh + 1, foot = thigh + 2;
  const double slope = 15 * DEG;
  double d[3], z[3] = {0, 0, 1}, nrm[3], sh[3], el[3], wr[3];
  set3(d, s * cos(slope), -sin(slope), 0); /* arm direction */
  v_cross(d, z, nrm);                       /* palm normal (down-ish) */
  v_norm(nrm);
  set3(sh, s * 0.20, 1.42, 0);
  axpy3(el, sh, 0.29, d);
  axpy3(wr, el, 0.25, d);
  memcpy(B->joint[uarm], sh, sizeof sh);
  memcpy(B->joint[farm], el, sizeof el);
  memcpy(B->joint[hand], wr, sizeof wr);
  B->parent[uarm] = B_CHEST;
  B->parent[farm] = uarm;
  B->parent[hand] = farm;
  add_capsule(B, uarm, 0.05, sh, el, 0.052, 0.042);
  add_capsule(B, farm, 0.02, el, wr, 0.041, 0.031);
  double palm[3];
  axpy3(palm, wr, 0.055, d);
  add_ellipsoid(B, hand, 0.02, palm, d, z, 0.065, 0.048, 0.022);
  /* three finger stubs fanned in the palm plane, and a thumb towards the front */
  for (int f = -1; f <= 1; f++) {
    double base[3], dir[3], tip[3], side[3];
    set3(side, 0, 0, 1);
    axpy3(base, palm, 0.045, d);
    axpy3(base, base, 0.024 * f, side);
    turn(dir, d, side, 32 * DEG * f);
    axpy3(tip, base, 0.055, dir);
    add_capsule(B, hand, 0.008, base, tip, 0.0135, 0.0115);
  }
  {
    double base[3], dir[3], tip[3];
    axpy3(base, palm, -0.01, d);
    base[2] += 0.035;
    turn(dir, d, z, 62 * DEG);
    axpy3(tip, base, 0.055, dir);
    add_capsule(B, hand, 0.008, base, tip, 0.015, 0.0125);
  }
  /* leg */
  double hip[3], knee[3], ank[3];
  set3(hip, s * 0.095, 0.92, 0);
  set3(knee, s * 0.105, 0.50, 0.012);
  set3(ank, s * 0.112, 0.095, -0.01);
  memcpy(B->joint[thigh], hip, sizeof hip);
  B->joint[thigh][2] += 0.02; /* likewise the hip hinge sits in front: less crushing in the groin */
  memcpy(B->joint[shin], knee, sizeof knee);
  /* the knee hinge sits behind the bone axis: less crushing at the back of the knee */
  B->joint[shin][2] -= 0.03;
  memcpy(B->joint[foot], ank, sizeof ank);
  B->parent[thigh] = B_PELVIS;
  B->parent[shin] = thigh;
  B->parent[foot] = shin;
  add_capsule(B, thigh, 0.04, hip, knee, 0.078, 0.052);
  add_capsule(B, shin, 0.025, knee, ank, 0.05, 0.034);
  double fc[3], x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
  set3(fc, s * 0.112, 0.047, 0.045);
  add_ellipsoid(B, foot, 0.03, fc, x, y, 0.047, 0.037, 0.11);
  for (int t = -1; t <= 1; t++) {
    double base[3], dir[3], tip[3];
    set3(base, s * 0.112 + 0.022 * t, 0.042, 0.125);
    set3(dir, 0.6 * t, 0, 1);
    v_norm(dir);
    axpy3(tip, base, 0.05, dir);
    add_capsule(B, foot, 0.008, base, tip, 0.0135, 0.0115);
  }
}

static void build_body(body *B) {
  memset(B, 0, sizeof *B);
  double x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, c[3], a[3], b[3];
  B->waist_y = 1.03;
  B->chest_y = 1.20;
  B->parent[B_PELVIS] = -1;
  set3(B->joint[B_PELVIS], 0, 0.95, 0);
  set3(B->joint[B_ABDOMEN], 0, B->waist_y, 0);
  B->parent[B_ABDOMEN] = B_PELVIS;
  set3(B->joint[B_CHEST], 0, B->chest_y, 0);
  B->parent[B_CHEST] = B_ABDOMEN;
  set3(B->joint[B_HEAD], 0, 1.45, 0);
  B->parent[B_HEAD] = B_CHEST;
  set3(c, 0, 0.96, 0);
  add_ellipsoid(B, B_TORSO, 0, c, x, y, 0.165, 0.115, 0.105);
  set3(c, 0, 1.13, 0);
  add_ellipsoid(B, B_TORSO, 0.06, c, x, y, 0.145, 0.14, 0.095);
  set3(c, 0, 1.31, 0);
  add_ellipsoid(B, B_TORSO, 0.06, c, x, y, 0.175, 0.155, 0.11);
  set3(a, 0, 1.42, 0);
  set3(b, 0, 1.56, 0.01);
  add_capsule(B, B_HEAD, 0.04, a, b, 0.056, 0.05);
  set3(c, 0, 1.645, 0.015);
  add_ellipsoid(B, B_HEAD, 0.04, c, x, y, 0.082, 0.105, 0.095);
  build_side(B, 1);
  build_side(B, -1);
}

/* ---- poses ---- */
typedef struct {
  int bone;
  double ax, ay, az, deg;
} rot;
#define MAXROT 16
typedef struct {
  const char *name;
  rot r[MAXROT];
  int n;
} pose_def;

/* Axes are in rest-pose world coordinates, angles in degrees; a right-side rotation mirroring a
 * left-side one uses the axis (ax, -ay, -az) and the same angle. */
static const double S15 = 0.25881904510252074, C15 = 0.96592582628906831;
static const pose_def POSES[] = {
    {"rest (arms 15 deg below horizontal)", {{0}}, 0},
    {"arms down, elbows slightly bent",
     {{B_UARM_L, 0, 0, 1, -60}, {B_UARM_R, 0, 0, -1, -60},
      {B_FARM_L, -S15, -C15, 0, 20}, {B_FARM_R, -S15, C15, 0, 20}}, 4},
    {"left leg raised (hip 70 deg, knee 75 deg), arms lowered",
     {{B_THIGH_L, -1, 0, 0, 70}, {B_SHIN_L, 1, 0, 0, 75}, {B_FOOT_L, -1, 0, 0, 10},
      {B_UARM_L, 0, 0, 1, -30}, {B_UARM_R, 0, 0, -1, -30}}, 5},
    {"torso twist (35 deg over two spine joints), head turned back 25 deg, elbows bent up 20 deg",
     {{B_ABDOMEN, 0, 1, 0, 17.5}, {B_CHEST, 0, 1, 0, 17.5}, {B_HEAD, 0, 1, 0, -25}, {B_FARM_L, 0, 0, 1, 20}, {B_FARM_R, 0, 0, -1, 20}}, 5},
    {"arms forward, elbows raised 45 deg",
     {{B_UARM_L, 0, 1, 0, -90}, {B_UARM_R, 0, -1, 0, -90},
      {B_FARM_L, 0, 0, 1, 45}, {B_FARM_R, 0, 0, -1, 45}}, 4},
    {"walking: arms swing, legs apart, knees bent, slight twist",
     {{B_UARM_L, 0, 0, 1, -62}, {B_UARM_L, -1, 0, 0, 25}, {B_UARM_R, 0, 0, -1, -62}, {B_UARM_R, -1, 0, 0, -25},
      {B_THIGH_L, -1, 0, 0, -18}, {B_THIGH_R, -1, 0, 0, 28}, {B_SHIN_L, 1, 0, 0, 15}, {B_SHIN_R, 1, 0, 0, 35},
      {B_ABDOMEN, 0, 1, 0, -5}, {B_CHEST, 0, 1, 0, -5}, {B_FARM_L, -S15, -C15, 0, 25}, {B_FARM_R, -S15, C15, 0, 15}}, 12},
};
#define NPOSES ((int)(sizeof POSES / sizeof POSES[0]))

int ss_synth_humanoid_pose_count(void) { return NPOSES; }
const char *ss_synth_humanoid_pose_name(int pose) { return pose >= 0 && pose < NPOSES ? POSES[pose].name : "?"; }

static void axis_angle(const double *axis, double ang, double *R) {
  double u[3] = {axis[0], axis[1], axis[2]};
  v_norm(u);
  double c = cos(ang), s = sin(ang), t = 1 - c;
  R[0] = t * u[0] * u[0] + c;
  R[1] = t * u[0] * u[1] - s * u[2];
  R[2] = t * u[0] * u[2] + s * u[1];
  R[3] = t * u[0] * u[1] + s * u[2];
  R[4] = t * u[1] * u[1] + c;
  R[5] = t * u[1] * u[2] - s * u[0];
  R[6] = t * u[0] * u[2] - s * u[1];
  R[7] = t * u[1] * u[2] + s * u[0];
  R[8] = t * u[2] * u[2] + c;
}
static void matmul3(const double *A, const double *B, double *C) {
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
  memcpy(C, T, sizeof T);
}
static void matvec3(const double *A, const double *x, double *y) {
  double t[3];
  for (int i = 0; i < 3; i++) t[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2];
  memcpy(y, t, sizeof t);
}

/* Forward kinematics: world transform of every bone; bones are numbered parents first. */
static void pose_transforms(const body *B, const pose_def *P, ssi_rigid *G) {
  double L[NBONES][9];
  for (int b = 0; b < NBONES; b++) axis_angle((double[3]){1, 0, 0}, 0, L[b]);
  for (int i = 0; i < P->n; i++) {
    double R[9], ax[3] = {P->r[i].ax, P->r[i].ay, P->r[i].az};
    axis_angle(ax, P->r[i].deg * DEG, R);
    matmul3(R, L[P->r[i].bone], L[P->r[i].bone]); /* later rotations act after earlier ones */
  }
  for (int b = 0; b < NBONES; b++) {
    const double *j = B->joint[b];
    double Rj[3], loc_t[3];
    matvec3(L[b], j, Rj);
    for (int d = 0; d < 3; d++) loc_t[d] = j[d] - Rj[d]; /* rotate about the joint */
    if (B->parent[b] < 0) {
      memcpy(G[b].R, L[b], sizeof G[b].R);
      memcpy(G[b].t, loc_t, sizeof G[b].t);
    } else {
      const ssi_rigid *p = &G[B->parent[b]];
      matmul3(p->R, L[b], G[b].R);
      matvec3(p->R, loc_t, G[b].t);
      for (int d = 0; d < 3; d++) G[b].t[d] += p->t[d];
    }
  }
}

/* ---- skinning weights ---- */
static ss_status skin_weights(const body *B, const ss_mesh *m, double **Wout, ss_error *err) {
  int nv = m->nv;
  double *W = calloc((size_t)nv * NBONES, sizeof(double));
  double *W2 = malloc(sizeof(double) * (size_t)nv * NBONES);
  int *deg = calloc((size_t)nv + 1, sizeof(int)), *adj = malloc(sizeof(int) * 3 * (size_t)m->nf);
  if (!W || !W2 || !deg || !adj) {
    free(W); free(W2); free(deg); free(adj);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for skinning weights");
  }
  for (int i = 0; i < nv; i++) {
    const double *x = m->V + 3 * (size_t)i;
    int best = 0;
    double bd = part_eval(&B->p[0], x);
    for (int p = 1; p < B->n; p++) {
      double d = part_eval(&B->p[p], x);
      if (d < bd) { bd = d; best = p; }
    }
    int bone = B->p[best].bone;
    if (bone == B_TORSO) bone = x[1] < B->waist_y ? B_PELVIS : x[1] < B->chest_y ? B_ABDOMEN : B_CHEST;
    W[(size_t)i * NBONES + bone] = 1;
  }
  /* 1-ring adjacency (CSR) from the oriented faces: each directed edge a->b appears once on a closed
   * oriented manifold, so the out-neighbours of a are exactly its 1-ring. */
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++) deg[m->F[3 * f + c] + 1]++;
  for (int i = 0; i < nv; i++) deg[i + 1] += deg[i];
  int *fill = malloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
  if (!fill) {
    free(W); free(W2); free(deg); free(adj);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for skinning weights");
  }
  memcpy(fill, deg, sizeof(int) * (size_t)nv);
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++) adj[fill[m->F[3 * f + c]]++] = m->F[3 * f + (c + 1) % 3];
  free(fill);
  /* Jacobi diffusion; after K steps the weights are exactly unchanged beyond K rings from a label
   * boundary, so the bands around joints are ~K edge lengths wide and the rest moves rigidly. */
  const int K = 16;
  for (int it = 0; it < K; it++) {
    for (int i = 0; i < nv; i++) {
      double *o = W2 + (size_t)i * NBONES;
      const double *w = W + (size_t)i * NBONES;
      int n = deg[i + 1] - deg[i];
      for (int b = 0; b < NBONES; b++) o[b] = 0.5 * w[b];
      for (int e = deg[i]; e < deg[i + 1]; e++) {
        const double *wn = W + (size_t)adj[e] * NBONES;
        for (int b = 0; b < NBONES; b++) o[b] += 0.5 * wn[b] / n;
      }
    }
    double *t = W; W = W2; W2 = t;
  }
  free(W2);
  free(deg);
  free(adj);
  *Wout = W;
  return SS_OK;
}

ss_status ss_synth_humanoid(int pose, ss_mesh *m, ss_error *err) {
  memset(m, 0, sizeof *m);
  if (pose < 0 || pose >= NPOSES)
    return ss_fail(err, SS_ERR_INVALID, "humanoid pose %d outside [0,%d]", pose, NPOSES - 1);
  body B;
  build_body(&B);
  /* lattice box: the parts' extents plus a margin; x symmetric so both sides sample alike */
  const double h = 0.0215;
  double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (int i = 0; i < B.n; i++) {
    const part *p = &B.p[i];
    for (int d = 0; d < 3; d++) {
      double l, u;
      if (p->type == P_CAPSULE) {
        double r = p->ra > p->rb ? p->ra : p->rb;
        l = fmin(p->a[d], p->b[d]) - r;
        u = fmax(p->a[d], p->b[d]) + r;
      } else {
        double r = fmax(p->r[0], fmax(p->r[1], p->r[2]));
        l = p->c[d] - r;
        u = p->c[d] + r;
      }
      lo[d] = fmin(lo[d], l);
      hi[d] = fmax(hi[d], u);
    }
  }
  double xm = fmax(-lo[0], hi[0]);
  lo[0] = -xm;
  hi[0] = xm;
  for (int d = 0; d < 3; d++) {
    lo[d] -= 3 * h;
    hi[d] += 3 * h;
  }
  ss_mesh rest;
  ss_status st = ssi_implicit_polygonize_bcc(body_field, &B, lo, hi, h, &rest, err);
  if (st) return st;
  st = ssi_implicit_remesh(body_field, &B, &rest, 0.0166, 10, err);
  if (st) { ss_mesh_free(&rest); return st; }
  if (pose == 0) {
    *m = rest;
    return SS_OK;
  }
  double *W = NULL;
  st = skin_weights(&B, &rest, &W, err);
  if (st) { ss_mesh_free(&rest); return st; }
  ssi_rigid G[NBONES];
  pose_def P = POSES[pose];
  pose_transforms(&B, &P, G);
  double *V = malloc(sizeof(double) * 3 * (size_t)rest.nv);
  if (!V) {
    free(W);
    ss_mesh_free(&rest);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for a humanoid pose");
  }
  st = ssi_dq_skin(rest.nv, rest.V, NBONES, W, G, V, err);
  free(W);
  if (st) { free(V); ss_mesh_free(&rest); return st; }
  free(rest.V);
  rest.V = V;
  *m = rest;
  return SS_OK;
}
