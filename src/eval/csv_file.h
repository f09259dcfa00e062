/* Reading and repairing the evaluation's resumable CSV files (csv_file.c). */
#ifndef SS_EVAL_CSV_FILE_H
#define SS_EVAL_CSV_FILE_H

#include <stdio.h>

/* Drops a partial last line left by an interrupted run, so appended rows start on a fresh line.
 * Returns 1 when the file holds at least one whole line (a header). */
int ssi_csv_repair_tail(const char *path);

/* Reads the next non-empty line of f into line (size bytes), without its line ending; *complete:
 * whether it ended with a newline (the cut last line of an interrupted run does not); *lineno is
 * advanced by the lines read. Returns 0 at the end of the file. */
int ssi_csv_next_line(FILE *f, char *line, int size, int *complete, int *lineno);

/* A whole field as an int (0) or not (1). */
int ssi_csv_parse_int(const char *s, int *v);
/* A whole field as a real (0) or not (1); empty_nan: an empty field is NAN. */
int ssi_csv_parse_real(const char *s, int empty_nan, double *v);

/* The threads of a run of `jobs` work units at once (0: the OpenMP default; 1 without OpenMP). */
int ssi_eval_threads(int jobs);

#endif
