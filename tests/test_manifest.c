/* The eval manifest reader (src/eval/manifest.c): a valid manifest's groups, meshes, pairs and
 * maps; each malformed input refused with SS_ERR_PARSE and a "NAME:LINE: what" message; the
 * per-group aggregation. */
#include "specseg/eval.h"
#include "testlib.h"

static ss_status rd(const char *text, ss_manifest *m, ss_error *e) {
  return ss_manifest_read_memory(text, strlen(text), "t.manifest", "/base", m, e);
}

/* the text is refused; the message starts with t.manifest:LINE: and contains `what` */
static void refused(const char *text, int line, const char *what) {
  ss_manifest m;
  ss_error e = {{0}};
  ss_status st = rd(text, &m, &e);
  char head[64];
  snprintf(head, sizeof head, "t.manifest:%d: ", line);
  CHECK_MSG(st == SS_ERR_PARSE && !strncmp(e.msg, head, strlen(head)) && strstr(e.msg, what),
            "status %d, message '%s' (want '%s...%s')", (int)st, e.msg, head, what);
  CHECK(m.nmeshes == 0 && m.meshes == NULL && m.px == NULL); /* nothing left allocated */
}

static void test_valid(void) {
  const char *text =
      "specseg-manifest 1   # comment\n"
      "\n"
      "group cats\n"
      "gt identity\n"
      "landmarks fps c1 7\n"
      "symmetry cat_sym.txt\n"
      "mesh meshes/c0.off\n"
      "mesh meshes/c1.off name c1\n"
      "mesh /abs/c2.ply landmarks lm2.txt\n"
      "pairs all\n"
      "group dogs\n"
      "gt maps\n"
      "mesh d0.off landmarks d0.lm\n"
      "mesh d1.off landmarks d1.lm symmetry d1.sym\n"
      "mesh d2.off landmarks d2.lm\n"
      "pair d0 d1\n"
      "pair d2 d0\n"
      "map d0 d1 maps/d0_d1.txt\n"
      "map d2 d0 maps/d2_d0.txt\n"
      "map d0 d2 maps/d0_d2.txt\n"
      "group birds\n"
      "mesh b0.off\nmesh b1.off\nmesh b2.off\nmesh b3.off\n"
      "pairs random 5 3\n"
      "group fish\n"
      "mesh f0.off\nmesh f1.off\nmesh f2.off\n"
      "pairs first\n";
  ss_manifest m;
  ss_error e = {{0}};
  CHECK_MSG(rd(text, &m, &e) == SS_OK, "%s", e.msg);
  CHECK(m.ngroups == 4 && m.nmeshes == 13 && m.nmaps == 3);
  CHECK(!strcmp(m.meshes[0].name, "c0") && !strcmp(m.meshes[0].path, "/base/meshes/c0.off"));
  CHECK(!strcmp(m.meshes[2].path, "/abs/c2.ply") && !strcmp(m.meshes[2].landmarks, "/base/lm2.txt"));
  CHECK(m.meshes[0].landmarks == NULL && m.meshes[4].symmetry && !strcmp(m.meshes[4].symmetry, "/base/d1.sym"));
  CHECK(m.groups[0].reference == 1 && m.groups[0].fps_seed == 7 && !strcmp(m.groups[0].symmetry, "/base/cat_sym.txt"));
  CHECK(m.groups[1].gt_maps == 1 && m.groups[1].pairs == SS_MANIFEST_PAIRS_LISTED && m.groups[1].reference == 3);
  CHECK(ss_manifest_find(&m, "d2") == 5 && ss_manifest_find(&m, "nope") == -1);
  CHECK(ss_manifest_map_path(&m, 3, 4) && !strcmp(ss_manifest_map_path(&m, 3, 4), "/base/maps/d0_d1.txt"));
  CHECK(ss_manifest_map_path(&m, 4, 3) == NULL);
  /* cats: all 6 ordered pairs, sorted; dogs: 2 listed; birds: 5 random distinct; fish: first -> 2 */
  CHECK(m.npairs == 6 + 2 + 5 + 2);
  CHECK(m.px[0] == 0 && m.py[0] == 1 && m.px[5] == 2 && m.py[5] == 1);
  CHECK(m.px[6] == 3 && m.py[6] == 4 && m.px[7] == 5 && m.py[7] == 3);
  int distinct = 1, inside = 1;
  for (int i = 8; i < 13; i++) {
    inside &= m.px[i] >= 6 && m.px[i] < 10 && m.py[i] >= 6 && m.py[i] < 10 && m.px[i] != m.py[i];
    for (int j = 8; j < i; j++) distinct &= !(m.px[i] == m.px[j] && m.py[i] == m.py[j]);
  }
  CHECK(distinct && inside);
  CHECK(m.px[13] == 10 && m.py[13] == 11 && m.px[14] == 10 && m.py[14] == 12);
  /* the same seed draws the same pairs */
  ss_manifest m2;
  CHECK(rd(text, &m2, &e) == SS_OK);
  CHECK(m2.npairs == m.npairs && !memcmp(m2.px, m.px, sizeof(int) * (size_t)m.npairs) &&
        !memcmp(m2.py, m.py, sizeof(int) * (size_t)m.npairs));
  ss_manifest_free(&m2);

  /* aggregation per group: rows of cats (0 -> 1, 1 -> 0) and of dogs */
  ss_eval_row r[4];
  memset(r, 0, sizeof r);
  for (int i = 0; i < 4; i++) r[i].landmarks = SS_LM_GT, r[i].pairing = -1;
  r[0].x = 0, r[0].y = 1, r[0].error = 0.1, r[0].error_sym = 0.05;
  r[1].x = 1, r[1].y = 0, r[1].error = 0.3, r[1].error_sym = 0.1;
  r[2].x = 1, r[2].y = 0, r[2].method = SS_METHOD_DIFF, r[2].error = 0.2;
  r[3].x = 3, r[3].y = 4, r[3].error = 0.5;
  double mean[4 * 4 * SS_EVAL_NMETHODS], msym[4 * 4 * SS_EVAL_NMETHODS];
  int count[4 * 4 * SS_EVAL_NMETHODS];
  CHECK(ss_manifest_aggregate(&m, r, 4, mean, msym, count, &e) == SS_OK);
  const int c0 = (0 * 4 + SS_LM_GT) * SS_EVAL_NMETHODS, c1 = (1 * 4 + SS_LM_GT) * SS_EVAL_NMETHODS;
  CHECK(count[c0] == 2 && fabs(mean[c0] - 0.2) < 1e-15 && fabs(msym[c0] - 0.075) < 1e-15);
  CHECK(count[c0 + SS_METHOD_DIFF] == 1 && count[c1] == 1 && fabs(mean[c1] - 0.5) < 1e-15);
  CHECK(count[(2 * 4 + SS_LM_GT) * SS_EVAL_NMETHODS] == 0 && isnan(mean[(2 * 4 + SS_LM_GT) * SS_EVAL_NMETHODS]));
  r[3].y = 0; /* a pair across groups */
  CHECK(ss_manifest_aggregate(&m, r, 4, mean, msym, count, &e) == SS_ERR_INVALID && strstr(e.msg, "not a pair of this manifest"));
  ss_manifest_free(&m);
  CHECK(m.nmeshes == 0 && m.meshes == NULL);

  /* no group line: one group "default"; pair lines alone select "listed"; CRLF line ends */
  CHECK(rd("specseg-manifest 1\r\nmesh a.off\r\nmesh b.off\r\nmesh c.off\r\npair c a\r\n", &m, &e) == SS_OK);
  CHECK(m.ngroups == 1 && !strcmp(m.groups[0].name, "default") && m.npairs == 1 && m.px[0] == 2 && m.py[0] == 0);
  ss_manifest_free(&m);
}

static void test_malformed(void) {
  const char *H = "specseg-manifest 1\n";
  char t[2048];
  refused("", 1, "not a specseg manifest");
  refused("# only a comment\n", 1, "not a specseg manifest");
  refused("mesh a.off\n", 1, "first line must be 'specseg-manifest 1'");
  refused("specseg-manifest 2\nmesh a.off\n", 1, "version '2' not supported");
  refused(H, 1, "no meshes");
#define R(body, line, what) (snprintf(t, sizeof t, "%s%s", H, body), refused(t, line, what))
  R("frobnicate x\n", 2, "unknown directive 'frobnicate'");
  R("group\n", 2, "'group' takes one name");
  R("group a\nmesh x.off\ngroup a\n", 4, "group 'a' declared twice");
  R("group a\ngroup b\nmesh x.off\nmesh y.off\n", 2, "group 'a' has no meshes");
  R("group a\nmesh x.off\nmesh y.off\ngroup b\n", 5, "group 'b' has no meshes");
  R("mesh\n", 2, "'mesh PATH");
  R("mesh a.off name\n", 2, "odd options");
  R("mesh a.off colour red\n", 2, "unknown mesh option 'colour'");
  R("mesh a.off landmarks x landmarks y\n", 2, "'landmarks' given twice");
  R("mesh a.off name n name m\n", 2, "'name' given twice");
  R("mesh d1/a.off\nmesh d2/a.off\n", 3, "mesh name 'a' used twice");
  R("gt maybe\nmesh a.off\n", 2, "'gt identity' or 'gt maps'");
  R("landmarks\nmesh a.off\n", 2, "'landmarks file FILE' or 'landmarks fps");
  R("landmarks file\n", 2, "'landmarks file FILE'");
  R("landmarks file a\nlandmarks file b\n", 3, "landmark file given twice");
  R("landmarks fps a -3\nmesh a.off\n", 2, "bad seed vertex '-3'");
  R("landmarks fps a 1 2\n", 2, "'landmarks fps [REFERENCE [SEED_VERTEX]]'");
  R("mesh a.off\nmesh b.off\nlandmarks fps zz\n", 4, "no mesh named 'zz'");
  R("symmetry\n", 2, "'symmetry FILE'");
  R("pairs some\n", 2, "'pairs all', 'pairs first'");
  R("pairs random 0 1\n", 2, "bad pair count '0'");
  R("pairs random 3 -1\n", 2, "bad seed '-1'");
  R("pairs random 3 x\n", 2, "bad seed 'x'");
  R("pairs all\npairs first\n", 3, "'pairs' given twice");
  R("group g\nmesh a.off\nmesh b.off\npairs random 3 1\n", 2, "3 random pairs requested, fewer ordered pairs exist");
  R("mesh a.off\n", 2, "group 'default' has no pairs");
  R("group g\nmesh a.off\nmesh b.off\npairs listed\n", 2, "group 'g' has no pairs");
  R("mesh a.off\nmesh b.off\npair a\n", 4, "'pair SOURCE TARGET'");
  R("mesh a.off\nmesh b.off\npair a c\n", 4, "no mesh named 'c'");
  R("mesh a.off\nmesh b.off\npair a a\n", 4, "pair of mesh 'a' with itself");
  R("group g\nmesh a.off\nmesh b.off\ngroup h\nmesh c.off\nmesh d.off\npair a c\n", 8, "mesh 'a' is not in group 'h'");
  R("mesh a.off\nmesh b.off\nmap a b\n", 4, "'map SOURCE TARGET FILE'");
  R("mesh a.off\nmesh b.off\nmap a b m.txt\n", 4, "'map' needs 'gt maps'");
  R("gt maps\nmesh a.off\nmesh b.off\nmap a b m.txt\nmap a b n.txt\n", 6, "second map of 'a' -> 'b'");
  R("gt maps\nmesh a.off\nmesh b.off\nmap a a m.txt\n", 5, "map of mesh 'a' onto itself");
  R("gt maps\nmesh a.off\nmesh b.off\nmap a b m.txt\n", 2, "no 'map' line for the pair 'b' -> 'a'");
  R("gt maps\nlandmarks file lm.txt\nmesh a.off\nmesh b.off\nmap a b m.txt\nmap b a n.txt\n", 2,
    "a group-wide landmark file needs identity ground truth");
  R("mesh a.off a b c d e f g h i j k l m n o\n", 2, "too many words");
#undef R
  /* a line over 8192 bytes; a NUL byte */
  static char big[9000];
  memset(big, 'x', sizeof big);
  memcpy(big, "specseg-manifest 1\nmesh ", 24);
  big[sizeof big - 1] = 0;
  refused(big, 2, "longer than 8192 bytes");
  ss_manifest m;
  ss_error e;
  CHECK(ss_manifest_read_memory("specseg-manifest 1\n\0mesh", 24, "t.manifest", NULL, &m, &e) == SS_ERR_PARSE &&
        strstr(e.msg, "NUL byte"));
  /* a missing file is SS_ERR_IO with the path */
  CHECK(ss_manifest_read("/nonexistent/x.manifest", &m, &e) == SS_ERR_IO && strstr(e.msg, "/nonexistent/x.manifest"));
}

int main(void) {
  test_valid();
  test_malformed();
  TEST_MAIN_END();
}
