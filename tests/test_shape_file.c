/* Prepared shapes (match/shape_file.c, match/match_shapes.c) and the checksummed-file helper they
 * share with the eval cache (util/blob.c): a round trip is bit-identical and matches exactly as the
 * meshes do; damaged, truncated, extended or other-version files are refused with a reason. */
#include "testlib.h"
#include "specseg/specseg.h"
#include "specseg/synth.h"
#include "util/blob.h"

#include <unistd.h>

/* head, left hand, right hand, left foot, right foot of the rest pose (as test_match.c) */
static void humanoid_landmarks(const ss_mesh *m, int lm[5]) {
  double best[5] = {-INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < m->nv; i++) {
    const double *p = m->V + 3 * (size_t)i;
    double score[5] = {p[1], p[0], -p[0], p[0] > 0.05 ? -p[1] + 0.1 * p[2] : -INFINITY,
                       p[0] < -0.05 ? -p[1] + 0.1 * p[2] : -INFINITY};
    for (int l = 0; l < 5; l++)
      if (score[l] > best[l]) best[l] = score[l], lm[l] = i;
  }
}

static int same_bytes(const void *a, const void *b, size_t n) {
  if (!a || !b) return a == b;
  return !memcmp(a, b, n);
}

static int same_shape(const ss_prepared_shape *a, const ss_prepared_shape *b) {
  const ss_segmentation *g = &a->prep.seg, *h = &b->prep.seg;
  size_t nv = (size_t)a->mesh.nv, wn = (size_t)g->work.nv, m = (size_t)g->m, k = (size_t)a->prep.kev;
  int ok = a->mesh.nv == b->mesh.nv && a->mesh.nf == b->mesh.nf && a->prep.kev == b->prep.kev && g->m == h->m &&
           g->work.nv == h->work.nv && g->work.nf == h->work.nf && a->has_signature == b->has_signature &&
           !memcmp(&a->seg, &b->seg, sizeof a->seg) && a->prep.area == b->prep.area && g->lambda2 == h->lambda2 &&
           g->ncrit_raw == h->ncrit_raw && g->empty_segments == h->empty_segments;
  if (!ok) return 0;
  ok = same_bytes(a->mesh.V, b->mesh.V, 24 * nv) && same_bytes(a->mesh.F, b->mesh.F, 12 * (size_t)a->mesh.nf) &&
       same_bytes(a->prep.evals, b->prep.evals, 8 * k) && same_bytes(a->prep.evecs, b->prep.evecs, 8 * k * nv) &&
       same_bytes(a->prep.M, b->prep.M, 8 * nv) && same_bytes(g->labels, h->labels, 4 * nv) &&
       same_bytes(g->centers, h->centers, 4 * m) && same_bytes(g->work.V, h->work.V, 24 * wn) &&
       same_bytes(g->work.F, h->work.F, 12 * (size_t)g->work.nf) && same_bytes(g->psi, h->psi, 4 * nv) &&
       same_bytes(g->phi, h->phi, 8 * wn) && same_bytes(g->crit, h->crit, 4 * m) &&
       same_bytes(g->crit_type, h->crit_type, m) && same_bytes(g->work_labels, h->work_labels, 4 * wn) &&
       same_bytes(g->work_dist, h->work_dist, 8 * wn) && !a->prep.crit_fields == !b->prep.crit_fields &&
       (!a->prep.crit_fields || same_bytes(a->prep.crit_fields, b->prep.crit_fields, 8 * wn * m)) &&
       a->prep.nprobe_cache == b->prep.nprobe_cache;
  for (int i = 0; ok && i < a->prep.nprobe_cache; i++) {
    const ss_fmap_probe_cache *c = &a->prep.probe_cache[i], *d = &b->prep.probe_cache[i];
    const size_t ck = (size_t)c->k, kk = ck * (ck + 1) / 2;
    ok = c->k == d->k && c->kd == d->kd && c->n_energies == d->n_energies && c->descr_step == d->descr_step &&
         c->sigma_factor == d->sigma_factor && c->nwks == d->nwks && c->kt == d->kt && !c->O == !d->O && !c->T == !d->T &&
         same_bytes(c->A, d->A, 8 * ck * c->nwks) && same_bytes(c->P, d->P, 8 * kk * c->nwks) &&
         (!c->O || same_bytes(c->O, d->O, 8 * ck * ck * c->nwks)) && (!c->T || same_bytes(c->T, d->T, 8 * kk * c->kt));
  }
  if (ok && a->has_signature) {
    const ss_centre_signature *s = &a->sig, *t = &b->sig;
    ok = s->m == t->m && s->nd == t->nd && s->volume_ratio == t->volume_ratio && s->orient_sign == t->orient_sign &&
         s->sigma_score == t->sigma_score && same_bytes(s->descr, t->descr, 8 * (size_t)s->m * s->nd) &&
         same_bytes(s->D, t->D, 8 * (size_t)s->m * s->m) && same_bytes(s->normals, t->normals, 24 * nv) &&
         same_bytes(s->sigma, t->sigma, 4 * (size_t)s->m) && same_bytes(s->centers, t->centers, 4 * (size_t)s->m) &&
         t->prep == &b->prep;
  }
  return ok && b->prep.mesh == &b->mesh;
}

static int same_result(const ss_match_result *a, const ss_match_result *b) {
  return a->nX == b->nX && a->kc == b->kc && a->pairs.n == b->pairs.n && same_bytes(a->map, b->map, 4 * (size_t)a->nX) &&
         same_bytes(a->C, b->C, 8 * (size_t)a->kc * a->kc) && same_bytes(a->pairs.sx, b->pairs.sx, 4 * (size_t)a->pairs.n) &&
         same_bytes(a->pairs.sy, b->pairs.sy, 4 * (size_t)a->pairs.n) &&
         same_bytes(a->centerX, b->centerX, 4 * (size_t)a->pairs.n) && a->refine_choice == b->refine_choice &&
         !strcmp(a->notes, b->notes);
}

/* the bytes b[0, n) as a file read back: the status and the message */
static ss_status read_bytes(const char *path, const unsigned char *b, size_t n, ss_error *e) {
  FILE *f = fopen(path, "wb");
  if (!f) return SS_ERR_IO;
  fwrite(b, 1, n, f);
  fclose(f);
  ss_prepared_shape s;
  ss_status st = ss_prepared_shape_read(path, &s, e);
  ss_prepared_shape_free(&s);
  ss_status sm = ss_prepared_shape_read_memory(b, n, path, &s, e); /* the same answer from memory */
  ss_prepared_shape_free(&s);
  return st == sm ? st : (ss_status)99;
}

static void damage_tests(const char *good, const char *dir) {
  size_t n = 0;
  unsigned char *b = (unsigned char *)tl_read_file(good, &n);
  CHECK(b && n > 1000);
  if (!b) return;
  char path[4200];
  snprintf(path, sizeof path, "%s/damaged.sss", dir);
  ss_error e = {{0}};
  CHECK(read_bytes(path, b, n, &e) == SS_OK);
  size_t key_end = (size_t)((unsigned char *)memchr(b, '\n', n) - b);
  size_t head_end = (size_t)((unsigned char *)memchr(b + key_end + 1, '\n', n - key_end - 1) - b);
  /* one flipped byte anywhere: in the options of the key line, in the payload line, in the payload */
  size_t at[] = {key_end - 3, key_end + 12, head_end - 2, head_end + 1, head_end + 40, n / 2, n - 1};
  for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
    b[at[i]] ^= 0x01;
    ss_status st = read_bytes(path, b, n, &e);
    CHECK_MSG(st == SS_ERR_PARSE && strstr(e.msg, "not used"), "flip at %zu: %d %s", at[i], (int)st, e.msg);
    b[at[i]] ^= 0x01;
  }
  /* truncated anywhere, or longer */
  size_t cut[] = {0, 5, key_end, head_end + 1, n / 3, n - 1};
  for (size_t i = 0; i < sizeof cut / sizeof cut[0]; i++) {
    ss_status st = read_bytes(path, b, cut[i], &e);
    CHECK_MSG(st == SS_ERR_PARSE, "cut at %zu: %d %s", cut[i], (int)st, e.msg);
  }
  CHECK(read_bytes(path, b, n / 3, &e) == SS_ERR_PARSE && strstr(e.msg, "truncated"));
  unsigned char *longer = malloc(n + 1);
  memcpy(longer, b, n), longer[n] = '\n';
  CHECK(read_bytes(path, longer, n + 1, &e) == SS_ERR_PARSE && strstr(e.msg, "longer"));
  free(longer);
  CHECK(read_bytes(path, b, n / 2, &e) == SS_ERR_PARSE); /* and never partly filled: checked by ASan (no leak) */
  /* another format version, another machine, not a prepared shape at all */
  CHECK(b[14] == '0' + SS_PREPARED_SHAPE_VERSION);
  b[14] = '2'; /* version 2: before the probe cache */
  CHECK(read_bytes(path, b, n, &e) == SS_ERR_PARSE && strstr(e.msg, "format version 2") && strstr(e.msg, "version 3"));
  b[14] = '0' + SS_PREPARED_SHAPE_VERSION;
  unsigned char *c = memchr(b, 'l', key_end); /* "le" -> "be" */
  if (c && c[1] == 'e') {
    *c = 'b';
    CHECK(read_bytes(path, b, n, &e) == SS_ERR_PARSE && strstr(e.msg, "byte order"));
    *c = 'l';
  }
  const char *off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  CHECK(read_bytes(path, (const unsigned char *)off, strlen(off), &e) == SS_ERR_PARSE && strstr(e.msg, "not a specseg"));
  CHECK(read_bytes(path, b, n, &e) == SS_OK); /* undamaged again */
  /* a file of the earlier checksum (byte-wise FNV-1a, "fnv1a64") is read as well, and checked */
  {
    CHECK(!memcmp(b + key_end + 1, "payload ", 8) && strstr((const char *)b + key_end + 1, " fnv1a64x4 "));
    const size_t pay = head_end + 1, plen = n - pay;
    uint64_t h = 1469598103934665603ull; /* the blob files' FNV start (blob.h) */
    for (size_t i = 0; i < n; i++)
      if (i <= key_end || i >= pay) h = (h ^ b[i]) * 1099511628211ull;
    unsigned char *old = malloc(n + 64);
    memcpy(old, b, key_end + 1);
    int hl = snprintf((char *)old + key_end + 1, 64, "payload %zu fnv1a64 %016llx\n", plen, (unsigned long long)h);
    memcpy(old + key_end + 1 + hl, b + pay, plen);
    const size_t on = key_end + 1 + (size_t)hl + plen;
    CHECK_MSG(read_bytes(path, old, on, &e) == SS_OK, "fnv1a64 file: %s", e.msg);
    old[on - 1] ^= 0x01;
    CHECK(read_bytes(path, old, on, &e) == SS_ERR_PARSE && strstr(e.msg, "checksum"));
    free(old);
  }
  ss_prepared_shape s;
  snprintf(path, sizeof path, "%s/absent.sss", dir);
  CHECK(ss_prepared_shape_read(path, &s, &e) == SS_ERR_IO);
  CHECK(ss_is_prepared_shape(b, n) && !ss_is_prepared_shape(off, strlen(off)) && !ss_is_prepared_shape(b, 5));
  free(b);
}

/* the helper the eval cache uses: its exact-key mode and messages */
static void blob_tests(const char *dir) {
  char path[4200], note[512];
  snprintf(path, sizeof path, "%s/blob.bin", dir);
  ssi_blob b = {0}, r;
  double v[3] = {1.5, -2, 3e300};
  int k = 7;
  SSI_PUT(&b, v, 3), SSI_PUT(&b, &k, 1);
  CHECK(!b.bad && b.n == 28);
  CHECK(ssi_blob_write(path, "tag-v1 x 1\n", &b) == 0);
  ssi_blob_free(&b);
  double w[3];
  int kk = 0;
  CHECK(ssi_blob_read(path, "tag-v1 x 1\n", NULL, 0, &r, note, sizeof note) == 1);
  CHECK(SSI_GET(&r, w, 3) && SSI_GET(&r, &kk, 1) && !memcmp(v, w, sizeof v) && kk == 7 && r.pos == r.n);
  CHECK(!SSI_GET(&r, &kk, 1) && r.bad); /* past the end */
  ssi_blob_free(&r);
  CHECK(ssi_blob_read(path, "tag-v1 x 2\n", NULL, 0, &r, note, sizeof note) == -1 && strstr(note, "another version"));
  CHECK(ssi_blob_read("/nonexistent/blob.bin", NULL, NULL, 0, &r, note, sizeof note) == 0);
  /* FNV-1a 64 from the eval cache's starting value (see blob.h), computed independently */
  CHECK(ssi_fnv1a(SSI_FNV_INIT, "a", 1) == 0x44bd8ad473cd9906ull);
  CHECK(ssi_fnv1a(14695981039346656037ull, "a", 1) == 0xaf63dc4c8601ec8cull); /* the published FNV-1a 64 of "a" */
  remove(path);
}

/* A file whose checksum is right but whose values are not (issue 32, item 2): each is refused by
 * the reader, naming what is wrong; and the landmark-free pairing given such a signature in memory
 * returns an error instead of crashing in its mirror-candidate search. v: the value to poison. */
static void poisoned_file(ss_prepared_shape *P, double *v, double bad, const char *what, const char *dir) {
  char path[4200];
  snprintf(path, sizeof path, "%s/poisoned.sss", dir);
  const double keep = *v;
  *v = bad;
  ss_error e = {{0}};
  ss_prepared_shape R;
  CHECK(ss_prepared_shape_write(path, P, &e) == SS_OK);
  ss_status st = ss_prepared_shape_read(path, &R, &e);
  CHECK_MSG(st == SS_ERR_PARSE && strstr(e.msg, "not used") && strstr(e.msg, what), "%s: %d %s", what, (int)st, e.msg);
  if (!st) ss_prepared_shape_free(&R);
  *v = keep;
  remove(path);
}

static void value_tests(ss_prepared_shape *PX, ss_prepared_shape *PY, const char *dir) {
  ss_centre_signature *s = &PX->sig;
  poisoned_file(PX, &s->descr[3], NAN, "signature's descriptors", dir);
  poisoned_file(PX, &s->D[1], INFINITY, "signature's distances", dir);
  poisoned_file(PX, &s->normals[7], NAN, "signature's normals", dir);
  poisoned_file(PX, &s->volume_ratio, NAN, "signature's volume ratio", dir);
  poisoned_file(PX, &PX->prep.evecs[100], NAN, "eigenvectors", dir);
  poisoned_file(PX, &PX->prep.evals[5], NAN, "eigenvalues", dir);
  poisoned_file(PX, &PX->prep.M[10], 0.0, "masses", dir);
  poisoned_file(PX, &PX->prep.M[11], -1.0, "masses", dir);
  poisoned_file(PX, &PX->prep.area, NAN, "area", dir);
  poisoned_file(PX, &PX->mesh.V[4], NAN, "non-finite coordinate", dir);
  poisoned_file(PX, &PX->prep.seg.work.V[4], INFINITY, "work mesh", dir);
  poisoned_file(PX, &PX->prep.seg.phi[2], NAN, "Fiedler", dir);
  poisoned_file(PX, &PX->prep.seg.lambda2, NAN, "Fiedler", dir);
  poisoned_file(PX, &PX->prep.seg.work_dist[3], NAN, "distances to the centres", dir);
  poisoned_file(PX, &PX->seg.cmcf_dt, -1.0, "segmentation options", dir);
  poisoned_file(PX, &PX->autopair.w_geo, NAN, "pairing options", dir);
  /* all distances NaN, or one descriptor: an error from the pairing, not a crash */
  const size_t mm = (size_t)s->m * s->m;
  double *D = malloc(sizeof(double) * mm);
  CHECK(D != NULL);
  if (!D) return;
  memcpy(D, s->D, sizeof(double) * mm);
  ss_error e = {{0}};
  ss_segment_pairs out = {0};
  ss_autopair_options o;
  ss_autopair_default_options(&o);
  for (size_t i = 0; i < mm; i++) s->D[i] = NAN;
  ss_status st = ss_pair_centres_auto(s, &PY->sig, &o, &out, NULL, &e);
  CHECK_MSG(st == SS_ERR_INVALID && strstr(e.msg, "not finite"), "NaN distances: %d %s", (int)st, e.msg);
  ss_segment_pairs_free(&out);
  memcpy(s->D, D, sizeof(double) * mm);
  const double d0 = s->descr[0];
  s->descr[0] = NAN;
  st = ss_pair_centres_auto(PY->sig.m <= s->m ? &PY->sig : s, PY->sig.m <= s->m ? s : &PY->sig, &o, &out, NULL, &e);
  CHECK_MSG(st == SS_ERR_INVALID && strstr(e.msg, "not finite"), "NaN descriptor: %d %s", (int)st, e.msg);
  ss_segment_pairs_free(&out);
  s->descr[0] = d0;
  free(D);
}

int main(void) {
  ss_error e = {{0}};
  char dir[] = "/tmp/test_shape_file_XXXXXX";
  if (!mkdtemp(dir)) return 1;
  blob_tests(dir);

  ss_mesh X = {0}, Y = {0};
  CHECK(ss_synth_humanoid(0, &X, &e) == SS_OK);
  CHECK(ss_synth_humanoid(2, &Y, &e) == SS_OK);
  int lm[5];
  humanoid_landmarks(&X, lm);
  ss_match_options o;
  ss_match_default_options(&o);
  CHECK(ss_match_eigenpairs(NULL, 5) == 150 && ss_match_eigenpairs(NULL, 0) == 150);
  {
    /* with landmarks and no hypotheses beside them nothing is refined further: the match's 110 */
    ss_match_options h0 = o;
    h0.autopair.hyp_landmarks = 0;
    CHECK(ss_match_eigenpairs(&h0, 5) == 110 && ss_match_eigenpairs(&h0, 0) == 150);
  }
  const int kev = ss_match_eigenpairs(&o, 5);

  /* prepare, write, read back: bit-identical */
  ss_prepared_shape PX, PY, RX, RY;
  CHECK(ss_prepared_shape_compute(&X, NULL, kev, &o.autopair, &PX, &e) == SS_OK);
  CHECK(ss_prepared_shape_compute(&Y, NULL, kev, &o.autopair, &PY, &e) == SS_OK);
  CHECK(PX.has_signature && PY.has_signature && PX.prep.kev == kev);
  /* the default match's probe cache: the STD start's basis (with the triple products) and the
   * segment-aided one's */
  CHECK(PX.prep.nprobe_cache == 2 && PX.prep.probe_cache[0].T && PX.prep.probe_cache[0].O && PX.prep.probe_cache[1].nwks > 0);
  char px[4200], py[4200];
  snprintf(px, sizeof px, "%s/x.sss", dir);
  snprintf(py, sizeof py, "%s/y.sss", dir);
  CHECK(ss_prepared_shape_write(px, &PX, &e) == SS_OK);
  CHECK(ss_prepared_shape_write(py, &PY, &e) == SS_OK);
  CHECK(ss_prepared_shape_read(px, &RX, &e) == SS_OK);
  CHECK_MSG(ss_prepared_shape_read(py, &RY, &e) == SS_OK, "%s", e.msg);
  CHECK(same_shape(&PX, &RX) && same_shape(&PY, &RY));

  /* the critical points' fields: exact distances, so symmetric between two critical points; the
   * pairing read from them is the one propagated from the landmarks (d(l, c) = d(c, l)) */
  {
    const ss_segmentation *g = &PX.prep.seg;
    CHECK(PX.prep.crit_fields && PY.prep.crit_fields);
    double worst = 0;
    for (int a = 0; a < g->m; a++)
      for (int b = 0; b < g->m; b++) {
        double dab = PX.prep.crit_fields[g->crit[b] + (size_t)g->work.nv * a];
        double dba = PX.prep.crit_fields[g->crit[a] + (size_t)g->work.nv * b];
        if (a == b) CHECK(dab == 0);
        else worst = fmax(worst, fabs(dab - dba) / dab);
      }
    CHECK_MSG(worst < 1e-12, "crit fields: d(a, b) and d(b, a) differ by %g relative", worst);
    ss_shape_prep qX = PX.prep, qY = PY.prep; /* shallow copies without the fields */
    qX.crit_fields = qY.crit_fields = NULL;
    ss_segment_pairs f = {0}, l = {0};
    CHECK(ss_pair_segments_prepared(&PX.prep, &PY.prep, 5, lm, lm, &o.pairing, &f, &e) == SS_OK);
    CHECK(ss_pair_segments_prepared(&qX, &qY, 5, lm, lm, &o.pairing, &l, &e) == SS_OK);
    CHECK(f.n == l.n && f.n >= 4 && same_bytes(f.sx, l.sx, 4 * (size_t)f.n) && same_bytes(f.sy, l.sy, 4 * (size_t)f.n));
    for (int p = 0; p < f.n && p < l.n; p++) CHECK(fabs(f.energy[p] - l.energy[p]) <= 1e-12 * fmax(1, l.energy[p]));
    ss_segment_pairs_free(&f), ss_segment_pairs_free(&l);
    int bad[5] = {lm[0], lm[1], lm[2], lm[3], X.nv};
    CHECK(ss_pair_segments_prepared(&PX.prep, &PY.prep, 5, bad, lm, &o.pairing, &f, &e) == SS_ERR_INVALID &&
          strstr(e.msg, "out of range"));
  }

  /* matching the read shapes gives what the meshes give: with landmarks and landmark-free (prepared
   * with exactly the eigenpairs the match needs, as a match from the meshes computes them: the same
   * count for both, enough for the further refinement of the map kept, so the read shapes serve both) */
  CHECK(ss_match_eigenpairs(&o, 0) == kev);
  for (int nl = 5; nl >= 0; nl -= 5) {
    ss_match_result a = {0}, c = {0}, d = {0};
    char wa[512], wc[512];
    const ss_prepared_shape *SX = &RX, *SY = &RY;
    CHECK(ss_match_warn(&X, &Y, nl, lm, lm, &o, &a, wa, sizeof wa, &e) == SS_OK);
    CHECK_MSG(ss_match_prepared_shapes(SX, SY, nl, lm, lm, &o, &c, wc, sizeof wc, &e) == SS_OK, "%s", e.msg);
    CHECK_MSG(same_result(&a, &c), "nl %d: the map from the prepared files differs from the meshes'", nl);
    CHECK(!strcmp(wa, wc) && c.t_segment == 0 && c.t_eigs == 0);
    /* a shallow copy of a prepared shape (its inner pointers left behind) matches the same */
    ss_prepared_shape CX = *SX;
    CX.prep.mesh = NULL, CX.sig.prep = NULL;
    CHECK(ss_match_prepared_shapes(&CX, SY, nl, lm, lm, &o, &d, NULL, 0, &e) == SS_OK && same_result(&a, &d));
    /* the map kept was refined further, to hyp_final_kmax (with landmarks too: the hypotheses beside
     * them), then polished on the surfaces: the same hypothesis as without those steps, and the map
     * ss_match_refine gives from that one's map (k 110 -> 150), through ss_map_polish */
    {
      CHECK(c.autopair.hyp_final_k == o.autopair.hyp_final_kmax && c.kc == o.autopair.hyp_final_kmax);
      ss_match_options o0 = o, ro = o;
      o0.autopair.hyp_final_kmax = 0, o0.autopair.hyp_final_polish = 0;
      ss_match_result b = {0};
      CHECK(ss_match_prepared_shapes(SX, SY, nl, lm, lm, &o0, &b, NULL, 0, &e) == SS_OK && b.autopair.hyp_final_k == 0);
      CHECK(b.autopair.hypothesis == c.autopair.hypothesis && b.autopair.confident == c.autopair.confident);
      ro.fmap.k = o.fmap.zoomout_kmax, ro.fmap.zoomout_kmax = o.autopair.hyp_final_kmax;
      int *rm = malloc(sizeof(int) * (size_t)X.nv);
      CHECK(rm && ss_match_refine(ss_prepared_shape_matched(SX), ss_prepared_shape_matched(SY), b.map, &ro, rm, NULL, &e) == SS_OK);
      CHECK(c.autopair.hyp_final_polished == 1 && b.autopair.hyp_final_polished == 0);
      CHECK(rm && ss_map_polish(ss_prepared_shape_matched(SX)->mesh, ss_prepared_shape_matched(SY)->mesh, rm, NULL, rm,
                                &e) == SS_OK);
      CHECK_MSG(rm && !memcmp(rm, c.map, sizeof(int) * (size_t)X.nv),
                "the further refinement and the polish are not ss_match_refine's then ss_map_polish's");
      int moved = 0;
      for (int i = 0; i < X.nv; i++) moved += b.map[i] != c.map[i];
      printf("%d landmarks: the further refinement to %d and the polish moved %d of %d images\n", nl, c.kc, moved, X.nv);
      free(rm);
      ss_match_result_free(&b);
    }
    ss_match_result_free(&a), ss_match_result_free(&c), ss_match_result_free(&d);
  }

  /* too few eigenpairs for the match: refused, naming the shape and the count */
  {
    ss_prepared_shape SX;
    ss_match_result r = {0};
    CHECK(ss_prepared_shape_compute(&X, NULL, 60, NULL, &SX, &e) == SS_OK && !SX.has_signature);
    CHECK(ss_match_prepared_shapes(&SX, &RY, 5, lm, lm, &o, &r, NULL, 0, &e) == SS_ERR_INVALID &&
          strstr(e.msg, "X (the first shape) was prepared with 60 eigenpairs") && strstr(e.msg, "needs 110"));
    ss_match_options small = o;
    small.fmap.zoomout_kmax = 55, small.fmap.descr_k = 50;
    CHECK_MSG(ss_match_prepared_shapes(&SX, &RY, 5, lm, lm, &small, &r, NULL, 0, &e) == SS_OK, "%s", e.msg);
    ss_match_result_free(&r);
    ss_prepared_shape_free(&SX);
  }

  /* a second component (a small sphere beside the body): ss_match_warn matches the body only when
   * landmark-free, and the prepared shape gives the same by preparing that part again */
  {
    ss_mesh S = {0}, Z = {0};
    CHECK(ss_synth_icosphere(2, &S, &e) == SS_OK);
    CHECK(ss_mesh_alloc(&Z, X.nv + S.nv, X.nf + S.nf, &e) == SS_OK);
    memcpy(Z.V, X.V, 24 * (size_t)X.nv), memcpy(Z.F, X.F, 12 * (size_t)X.nf);
    for (int i = 0; i < S.nv; i++)
      for (int j = 0; j < 3; j++) Z.V[3 * (size_t)(X.nv + i) + j] = 0.05 * S.V[3 * (size_t)i + j] + (j == 0 ? 3.0 : 0.0);
    for (int f = 0; f < 3 * S.nf; f++) Z.F[3 * (size_t)X.nf + f] = S.F[f] + X.nv;
    ss_prepared_shape PZ, PW;
    ss_match_result a = {0}, c = {0};
    char wa[1024], wc[1024];
    ss_match_options q = o; /* smaller and unrefined: this part is about which components are matched */
    q.seg.target_faces = 3000, q.refine = SS_REFINE_NONE, q.fmap.descr_k = q.fmap.k = 30;
    q.autopair.descr_k = q.autopair.orient_descr_k = 40;
    const int kq = ss_match_eigenpairs(&q, 0);
    CHECK(kq == 40);
    CHECK_MSG(ss_prepared_shape_compute(&Z, &q.seg, kq, &q.autopair, &PZ, &e) == SS_OK, "%s", e.msg);
    CHECK(ss_prepared_shape_compute(&Y, &q.seg, kq, &q.autopair, &PW, &e) == SS_OK);
    CHECK(!PZ.has_signature && PW.has_signature); /* two components, one */
    CHECK(ss_match_warn(&Z, &Y, 0, NULL, NULL, &q, &a, wa, sizeof wa, &e) == SS_OK);
    CHECK_MSG(ss_match_prepared_shapes(&PZ, &PW, 0, NULL, NULL, &q, &c, wc, sizeof wc, &e) == SS_OK, "%s", e.msg);
    CHECK(same_result(&a, &c) && strstr(wc, wa) == wc && strstr(wc, "prepared data not used"));
    ss_match_result_free(&a), ss_match_result_free(&c);
    ss_prepared_shape_free(&PZ), ss_prepared_shape_free(&PW);
    ss_mesh_free(&S), ss_mesh_free(&Z);
  }

  damage_tests(px, dir);
  value_tests(&PX, &PY, dir);

  ss_prepared_shape_free(&PX), ss_prepared_shape_free(&PY), ss_prepared_shape_free(&RX), ss_prepared_shape_free(&RY);
  ss_mesh_free(&X), ss_mesh_free(&Y);
  char cmd[4300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd)) fprintf(stderr, "could not remove %s\n", dir);
  TEST_MAIN_END();
}
