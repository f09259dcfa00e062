/* The help text of specseg eval --benchmark, shared by `specseg eval --help` (cmd_eval.c) and
 * `specseg eval --benchmark DIR --help` (cmd_eval_benchmark.c). */
#ifndef SPECSEG_CLI_EVAL_BENCHMARK_H
#define SPECSEG_CLI_EVAL_BENCHMARK_H

#define CLI_EVAL_BENCHMARK_HELP_TEXT \
    "The field's benchmark (--benchmark DIR): meshes in DIR (or DIR/vtx_5k, DIR/off, DIR/shapes), per mesh NAME\n" \
    "its ground-truth points corres/NAME.vts (one 1-based vertex a line, line k the same point on every shape)\n" \
    "and optionally corres/NAME.sym.vts (the left-right mirror points); pairs from --pairs FILE, else\n" \
    "DIR/test_pairs.txt, else every ordered pair. Per pair, our map (landmark-free by default: what\n" \
    "'specseg match X Y' gives) and each --maps folder's map are scored alike: for every point k both files\n" \
    "have, d_Y(map(x_k), y_k) / sqrt(area(Y)) with exact geodesics (as 'specseg error'); x 100 as printed.\n" \
    "A missing or broken mesh, points file or map file skips its pairs with a warning; the run goes on.\n" \
    "Outputs in --out OUTDIR: maps/X__Y.txt (ours), pairs.csv (one row per method and pair; also the resume\n" \
    "state), summary.json, curves.png (cumulative error curves), and the table per method and class\n" \
    "(the name without its trailing digits): mean x 100, median, % of pairs above 5, pairs skipped.\n" \
    "  --benchmark DIR     the benchmark folder\n" \
    "  --out, -o OUTDIR    the output folder (default specseg_benchmark); a re-run resumes: rows scored\n" \
    "                      there are kept, the others computed\n" \
    "  --pairs FILE        the pairs (two names a line, tab or blank separated) instead of test_pairs.txt\n" \
    "  --max-pairs N       N pairs drawn from the list (seeded; default all)\n" \
    "  --seed S            seed of --max-pairs, >= 0 (default 1)\n" \
    "  --landmarks L       our maps: none (default, landmark-free) or gt:N, N ground-truth points as landmarks\n" \
    "                      (Euclidean farthest-point sampling over the points of the first shape, from its\n" \
    "                      point 0), 1..64; the method is then named specseg_gtN (use another --out)\n" \
    "  --maps NAME=MAPDIR  an external method: MAPDIR/X__Y.txt or .npy per pair, line i = vertex of Y for\n" \
    "                      vertex i of X (0-based, as 'specseg match' writes); repeatable (at most 15)\n" \
    "  --no-match          no maps of ours: score the --maps folders only\n" \
    "  --cache DIR         prepared shapes kept in DIR (NAME_<key>.sss, specseg prepare's format)\n" \
    "  --jobs N            pairs (and shapes) at once, 1..1024 (default: the OpenMP default)\n" \
    "  --shard I/N         only the I-th of N slices of the pairs (each to its own --out; then eval merge)\n" \
    "  --title TEXT        the name in the table, summary.json and curves.png (default: DIR's name)\n" \
    "  --quiet             no progress bar or stage messages (warnings stay)\n" \
    "  --json              the summary (summary.json's text) on standard output instead of the table\n" \
    "  specseg eval merge OUTDIR/pairs.csv... --out DIR [--title T] [--json]: the shards' rows in one\n" \
    "                      pairs.csv, summary.json, curves.png and table in DIR (a folder argument: its pairs.csv)\n"

/* 1 when path is a folder or a CSV whose header is the benchmark's pairs.csv (eval merge's choice) */
int cli_is_benchmark_csv(const char *path);
int cmd_eval_benchmark(int argc, char **argv);
int cmd_eval_benchmark_merge(int argc, char **argv);

#endif
