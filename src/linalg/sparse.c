#include "specseg/core.h"

#include <stdlib.h>
#include <string.h>

ss_status ss_sparse_from_triplets(int nrows, int ncols, size_t nnz, const int *I, const int *J,
                                  const double *X, ss_sparse *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  if (nrows < 0 || ncols < 0) return ss_fail(err, SS_ERR_INVALID, "negative sparse matrix size");
  int *cnt = calloc((size_t)ncols + 1, sizeof(int));
  int *ri = malloc(sizeof(int) * (nnz ? nnz : 1));
  double *vv = malloc(sizeof(double) * (nnz ? nnz : 1));
  if (!cnt || !ri || !vv) {
    free(cnt); free(ri); free(vv);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory building a sparse matrix");
  }
  for (size_t k = 0; k < nnz; k++) {
    if (I[k] < 0 || I[k] >= nrows || J[k] < 0 || J[k] >= ncols) {
      free(cnt); free(ri); free(vv);
      return ss_fail(err, SS_ERR_INVALID, "sparse triplet (%d,%d) out of range %dx%d", I[k], J[k], nrows, ncols);
    }
    cnt[J[k] + 1]++;
  }
  for (int j = 0; j < ncols; j++) cnt[j + 1] += cnt[j];
  int *pos = malloc(sizeof(int) * ((size_t)ncols + 1));
  if (!pos) { free(cnt); free(ri); free(vv); return ss_fail(err, SS_ERR_NOMEM, "out of memory"); }
  memcpy(pos, cnt, sizeof(int) * ((size_t)ncols + 1));
  for (size_t k = 0; k < nnz; k++) {
    int p = pos[J[k]]++;
    ri[p] = I[k];
    vv[p] = X[k];
  }
  free(pos);
  /* sort each column by row (insertion sort: columns are short) and merge duplicates */
  int w = 0;
  int start = 0;
  for (int j = 0; j < ncols; j++) {
    int end = cnt[j + 1];
    for (int a = start + 1; a < end; a++) {
      int r = ri[a]; double x = vv[a]; int b = a - 1;
      while (b >= start && ri[b] > r) { ri[b + 1] = ri[b]; vv[b + 1] = vv[b]; b--; }
      ri[b + 1] = r; vv[b + 1] = x;
    }
    int colstart = w;
    for (int a = start; a < end; a++) {
      if (w > colstart && ri[w - 1] == ri[a]) vv[w - 1] += vv[a];
      else { ri[w] = ri[a]; vv[w] = vv[a]; w++; }
    }
    start = end;
    cnt[j] = colstart;
  }
  cnt[ncols] = w;
  out->nrows = nrows; out->ncols = ncols;
  out->colptr = cnt; out->rowind = ri; out->val = vv;
  return SS_OK;
}

void ss_sparse_free(ss_sparse *A) {
  if (!A) return;
  free(A->colptr); free(A->rowind); free(A->val);
  memset(A, 0, sizeof *A);
}

void ss_sparse_matvec(const ss_sparse *A, const double *x, double *y) {
  for (int i = 0; i < A->nrows; i++) y[i] = 0;
  for (int j = 0; j < A->ncols; j++) {
    double xj = x[j];
    for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++) y[A->rowind[p]] += A->val[p] * xj;
  }
}
