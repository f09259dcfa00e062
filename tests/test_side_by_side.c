/* ssi_run_both (util/side_by_side.c): two tasks of one call side by side on two OpenMP threads, each
 * with single-threaded parallel regions inside; one after the other otherwise; the first task's
 * error first. */
#include "util/side_by_side.h"
#include "testlib.h"

#include <omp.h>

typedef struct task {
  int fail;   /* status to return (0: none) */
  int ran, thread, team, inner_team, order;
} task;

static int clock_ = 0; /* order of the runs (one after the other: a before b) */

static ss_status task_run(void *arg, ss_error *err) {
  task *t = arg;
  t->ran = 1;
  t->thread = omp_get_thread_num();
  t->team = omp_get_num_threads();
#pragma omp atomic capture
  t->order = clock_++;
  int inner = 0;
#pragma omp parallel
  {
#pragma omp single
    inner = omp_get_num_threads();
  }
  t->inner_team = inner;
  return t->fail ? ss_fail(err, (ss_status)t->fail, "task %s failed", t->fail == SS_ERR_INVALID ? "a" : "b") : SS_OK;
}

int main(void) {
  ss_error e;
  omp_set_num_threads(2);
  /* side by side: two threads, one each, single-threaded inside */
  {
    task a = {0}, b = {0};
    CHECK(ssi_run_both(task_run, &a, task_run, &b, 1, &e) == SS_OK);
    CHECK(a.ran && b.ran && a.team == 2 && b.team == 2 && a.thread != b.thread);
    CHECK(a.inner_team == 1 && b.inner_team == 1);
  }
  /* both = 0, one thread, or inside an active parallel region: one after the other, a first */
  for (int mode = 0; mode < 3; mode++) {
    task a = {0}, b = {0};
    clock_ = 0;
    if (mode == 0) CHECK(ssi_run_both(task_run, &a, task_run, &b, 0, &e) == SS_OK);
    if (mode == 1) {
      omp_set_num_threads(1);
      CHECK(ssi_run_both(task_run, &a, task_run, &b, 1, &e) == SS_OK);
      omp_set_num_threads(2);
    }
    if (mode == 2) {
      ss_status st = SS_ERR_INVALID;
#pragma omp parallel num_threads(2)
      {
#pragma omp single
        st = ssi_run_both(task_run, &a, task_run, &b, 1, &e);
      }
      CHECK(st == SS_OK);
    }
    /* (inside the region the tasks see its team of 2, on the one thread that called; with both = 0
     * their own regions have the two threads) */
    CHECK_MSG(a.ran && b.ran && a.thread == b.thread && a.team == (mode == 2 ? 2 : 1) && b.team == a.team &&
                  a.inner_team == (mode == 0 ? 2 : 1) && a.order == 0 && b.order == 1,
              "mode %d", mode);
  }
  /* errors: a's first; b's when a succeeds; one after the other, b does not run after a failed */
  {
    task a = {.fail = SS_ERR_INVALID}, b = {.fail = SS_ERR_NUMERIC};
    CHECK(ssi_run_both(task_run, &a, task_run, &b, 1, &e) == SS_ERR_INVALID && strstr(e.msg, "task a"));
    CHECK(a.ran && b.ran);
    task c = {0}, d = {.fail = SS_ERR_NUMERIC};
    CHECK(ssi_run_both(task_run, &c, task_run, &d, 1, &e) == SS_ERR_NUMERIC && strstr(e.msg, "task b"));
    task f = {.fail = SS_ERR_INVALID}, g = {0};
    CHECK(ssi_run_both(task_run, &f, task_run, &g, 0, &e) == SS_ERR_INVALID && f.ran && !g.ran);
    CHECK(ssi_run_both(task_run, &c, task_run, &d, 1, NULL) == SS_ERR_NUMERIC); /* err may be NULL */
  }
  TEST_MAIN_END();
}
