/* Internal: two independent tasks of one call, side by side on two OpenMP threads. */
#ifndef SS_UTIL_SIDE_BY_SIDE_H
#define SS_UTIL_SIDE_BY_SIDE_H

#include "specseg/core.h"

typedef ss_status (*ssi_task_fn)(void *arg, ss_error *err);

/* Runs fa(a) and fb(b). Side by side, one thread each, when `both` is nonzero and OpenMP gives this
 * call two threads outside any active parallel region: nested parallelism is off by default, so the
 * parallel regions inside each task run single-threaded and each task's result is the one it has
 * alone. Otherwise fa, then fb unless fa failed. Returns fa's failure first (its message in err),
 * else fb's, else SS_OK. The tasks must not write the same memory. */
ss_status ssi_run_both(ssi_task_fn fa, void *a, ssi_task_fn fb, void *b, int both, ss_error *err);

#endif
