/* The two resumable CSV files of the evaluation (Table 1's rows, the benchmark's pairs.csv) share
 * how an interrupted run is repaired and how their lines are read. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "csv_file.h"
#include "util/c_locale.h"

#ifdef _OPENMP
#include <omp.h>
#endif

int ssi_csv_repair_tail(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  fseek(f, 0, SEEK_END);
  long size = ftell(f), keep = 0;
  for (long pos = size - 1; pos >= 0; pos--) {
    fseek(f, pos, SEEK_SET);
    if (fgetc(f) == '\n') { keep = pos + 1; break; }
  }
  fclose(f);
  if (keep < size && truncate(path, keep)) return keep > 0;
  return keep > 0;
}

int ssi_csv_next_line(FILE *f, char *line, int size, int *complete, int *lineno) {
  for (;;) {
    if (!fgets(line, size, f)) return 0;
    ++*lineno;
    size_t len = strlen(line);
    *complete = len > 0 && line[len - 1] == '\n';
    line[strcspn(line, "\r\n")] = 0;
    if (line[0]) return 1;
  }
}

int ssi_csv_parse_int(const char *s, int *v) {
  char *end;
  errno = 0;
  long x = strtol(s, &end, 10);
  if (end == s || *end || errno || x < -2147483647L || x > 2147483647L) return 1;
  *v = (int)x;
  return 0;
}

int ssi_csv_parse_real(const char *s, int empty_nan, double *v) {
  if (empty_nan && !*s) { *v = NAN; return 0; }
  char *end;
  *v = ssi_strtod_c(s, &end);
  return end == s || *end;
}

int ssi_eval_threads(int jobs) {
#ifdef _OPENMP
  return jobs > 0 ? jobs : omp_get_max_threads();
#else
  (void)jobs;
  return 1;
#endif
}
