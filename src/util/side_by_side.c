/* Two independent tasks side by side (see side_by_side.h): the shapes of a match, a shape's
 * segmentation and eigenpairs. On two cores the stages of one shape leave the second core mostly
 * idle (their parallel regions are short), so whole tasks per thread use it better. */
#include "util/side_by_side.h"

#ifdef _OPENMP
#include <omp.h>
#endif

ss_status ssi_run_both(ssi_task_fn fa, void *a, ssi_task_fn fb, void *b, int both, ss_error *err) {
  ss_error ea = {{0}}, eb = {{0}};
  ss_status sa = SS_OK, sb = SS_OK;
  int two = 0;
#ifdef _OPENMP
  two = both && omp_get_max_threads() > 1 && !omp_in_parallel();
#else
  (void)both;
#endif
  if (two) {
    /* thread 0 runs a, thread 1 b (sections could hand both to the thread that arrives first); a
     * team of one (a thread limit) runs both */
#pragma omp parallel num_threads(2)
    {
      const int t = omp_get_thread_num(), nt = omp_get_num_threads();
      if (t == 0) sa = fa(a, &ea);
      if (t == 1 || (nt == 1 && !sa)) sb = fb(b, &eb);
    }
  } else {
    sa = fa(a, &ea);
    if (!sa) sb = fb(b, &eb);
  }
  if (sa || sb) {
    if (err) *err = sa ? ea : eb;
    return sa ? sa : sb;
  }
  return SS_OK;
}
