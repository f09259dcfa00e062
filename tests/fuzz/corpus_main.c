/* Runs a fuzz harness (tests/fuzz/fuzz_*.c, linked in) over every file of the folders given: the
 * corpus as regression inputs in ordinary builds (any compiler, no libFuzzer), one CTest per
 * harness. A violated property aborts; exit 0 when every input went through. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int run_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  size_t cap = 1 << 12, n = 0;
  unsigned char *b = malloc(cap);
  for (size_t r; b && (r = fread(b + n, 1, cap - n, f)) > 0;) {
    n += r;
    if (n == cap) {
      unsigned char *q = realloc(b, cap *= 2);
      if (!q) { free(b); b = NULL; }
      else b = q;
    }
  }
  fclose(f);
  if (!b) return -1;
  LLVMFuzzerTestOneInput(b, n);
  free(b);
  return 0;
}

int main(int argc, char **argv) {
  int files = 0;
  for (int a = 1; a < argc; a++) {
    DIR *d = opendir(argv[a]);
    if (!d) { fprintf(stderr, "%s: cannot open the folder\n", argv[a]); return 1; }
    for (struct dirent *e; (e = readdir(d));) {
      if (e->d_name[0] == '.') continue;
      char path[4096];
      snprintf(path, sizeof path, "%s/%s", argv[a], e->d_name);
      struct stat st;
      if (stat(path, &st) || !S_ISREG(st.st_mode)) continue;
      if (run_file(path)) { fprintf(stderr, "%s: cannot read\n", path); closedir(d); return 1; }
      files++;
    }
    closedir(d);
  }
  printf("%d inputs, no finding\n", files);
  return files > 0 ? 0 : 77; /* an empty corpus checks nothing */
}
