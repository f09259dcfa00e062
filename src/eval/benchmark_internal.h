/* Internals shared by the benchmark's files (benchmark_set.c, benchmark_csv.c, benchmark_score.c,
 * benchmark_run.c). */
#ifndef SS_EVAL_BENCHMARK_INTERNAL_H
#define SS_EVAL_BENCHMARK_INTERNAL_H

#include "specseg/eval.h"

#include <stdio.h>

char *bm_strdup(const char *s);
/* dir/name, malloc'd */
char *bm_join(const char *dir, const char *name);
int bm_is_dir(const char *path);
/* names with their numbers compared by value, then as strings: a total order */
int bm_name_cmp(const char *a, const char *b);
/* index of a shape name in b (sorted), -1 when absent */
int bm_find_shape(const ss_benchmark_set *b, const char *name);
/* methods named "specseg..." first, then by name */
int bm_method_cmp(const char *a, const char *b);
/* rows by (method, x, y) */
int bm_row_cmp(const ss_benchmark_row *a, const ss_benchmark_row *b);
/* appends "; " and the text to notes (cut at its size) */
void bm_note(char *notes, size_t size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* JSON helpers: a string literal (escaped), a real (%.17g, null for NaN / inf) */
void bm_json_str(FILE *f, const char *s);
void bm_json_num(FILE *f, double v);

#endif
