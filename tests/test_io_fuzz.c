/* Deterministic mutation fuzzing of the mesh readers: valid OFF / OBJ / PLY (ascii, binary LE, BE)
 * files get random byte flips, deletions, insertions of digits / signs / separators and truncations.
 * Every outcome must be either a valid mesh (all indices in range, at least one face) or an error
 * whose message starts with "PATH:" — never a crash, a hang or a sanitizer report (run under ASan). */
#include <stdint.h>
#include <unistd.h>

#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "testlib.h"

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static uint32_t rnd(void) {
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return (uint32_t)(rng >> 11);
}

int main(void) {
  char dir[] = "/tmp/ss_test_fuzz_XXXXXX";
  if (!mkdtemp(dir)) return 2;
  ss_mesh m;
  ss_error err;
  CHECK(ss_synth_icosphere(1, &m, &err) == SS_OK);
  unsigned char *rgb = malloc(3 * (size_t)m.nv);
  for (int i = 0; i < 3 * m.nv; i++) rgb[i] = (unsigned char)i;
  const char *names[] = {"s.off", "s.ply", "le.ply", "be.ply", "s.obj"};
  char paths[5][256], out[5][256];
  for (int k = 0; k < 5; k++) {
    snprintf(paths[k], sizeof paths[k], "%s/%s", dir, names[k]);
    snprintf(out[k], sizeof out[k], "%s/m_%s", dir, names[k]);
  }
  CHECK(ss_write_off(paths[0], &m, rgb, &err) == SS_OK);
  CHECK(ss_write_ply(paths[1], &m, rgb, SS_PLY_ASCII, &err) == SS_OK);
  CHECK(ss_write_ply(paths[2], &m, rgb, SS_PLY_BINARY_LE, &err) == SS_OK);
  CHECK(ss_write_ply(paths[3], &m, NULL, SS_PLY_BINARY_BE, &err) == SS_OK);
  {
    FILE *f = fopen(paths[4], "wb");
    for (int i = 0; i < m.nv; i++) fprintf(f, "v %.6f %.6f %.6f\n", m.V[3 * i], m.V[3 * i + 1], m.V[3 * i + 2]);
    for (int i = 0; i < m.nf; i += 2)
      fprintf(f, "f %d/1 %d//2 %d\n", m.F[3 * i] + 1, m.F[3 * i + 1] - m.nv, m.F[3 * i + 2] + 1);
    fclose(f);
  }
  static const char ins[] = "0123456789-+. \n#eE/x";
  int rounds = 400, crashes = 0, accepted = 0, rejected = 0;
  for (int k = 0; k < 5; k++) {
    size_t n0;
    unsigned char *orig = (unsigned char *)tl_read_file(paths[k], &n0);
    CHECK(orig != NULL);
    if (!orig) continue;
    unsigned char *buf = malloc(n0 + 64);
    for (int r = 0; r < rounds; r++) {
      size_t n = n0;
      memcpy(buf, orig, n0);
      int muts = 1 + (int)(rnd() % 4);
      for (int q = 0; q < muts && n > 0; q++) {
        size_t at = rnd() % n;
        switch (rnd() % 5) {
          case 0: buf[at] ^= (unsigned char)(1u << (rnd() % 8)); break;              /* bit flip */
          case 1: buf[at] = (unsigned char)rnd(); break;                              /* random byte */
          case 2: memmove(buf + at, buf + at + 1, n - at - 1); n--; break;            /* delete */
          case 3:                                                                     /* insert */
            if (n < n0 + 60) {
              memmove(buf + at + 1, buf + at, n - at);
              buf[at] = (unsigned char)ins[rnd() % (sizeof ins - 1)];
              n++;
            }
            break;
          default: n = at; break;                                                     /* truncate */
        }
      }
      FILE *f = fopen(out[k], "wb");
      fwrite(buf, 1, n, f);
      fclose(f);
      memset(&err, 0, sizeof err);
      ss_mesh r_;
      ss_status st = ss_read_mesh(out[k], &r_, &err);
      if (st == SS_OK) {
        int valid = r_.nf > 0 && r_.nv > 0;
        for (size_t i = 0; i < 3 * (size_t)r_.nf && valid; i++) valid = r_.F[i] >= 0 && r_.F[i] < r_.nv;
        ss_mesh_report rep;
        valid = valid && ss_mesh_check(&r_, &rep, &err) == SS_OK;
        if (!valid) crashes++;
        accepted++;
      } else {
        if (strncmp(err.msg, out[k], strlen(out[k])) || err.msg[strlen(out[k])] != ':') {
          crashes++;
          fprintf(stderr, "bad message for %s round %d: %s\n", names[k], r, err.msg);
        }
        if (r_.V || r_.F || r_.nv || r_.nf) crashes++;
        rejected++;
      }
      ss_mesh_free(&r_);
    }
    free(buf);
    free(orig);
  }
  CHECK_MSG(crashes == 0, "%d invalid outcomes", crashes);
  CHECK(rejected > 0 && accepted > 0);
  printf("fuzz: %d mutated files, %d accepted (valid meshes), %d rejected with a located message\n", accepted + rejected,
         accepted, rejected);
  for (int k = 0; k < 5; k++) {
    unlink(paths[k]);
    unlink(out[k]);
  }
  rmdir(dir);
  free(rgb);
  ss_mesh_free(&m);
  TEST_MAIN_END();
}
