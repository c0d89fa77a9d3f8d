#pragma once
// A supernode's dense block factored on several threads: the top separators of a nested dissection, whose
// dense work is a large share of the whole (bunny00: a fifth) and would otherwise run on one thread after
// the subtrees.
//
// The block is nsrow x nscol, column-major with leading dimension nsrow: its first nscol rows are the
// diagonal block (lower triangle read), the rest the rows below. On return the diagonal block holds its
// lower Cholesky factor L11 and the rows below L21 = B21 L11'^-1, as dpotrf and dtrsm leave them. Panels of
// columns go one after another: each is factored on the calling thread, then the rows below it are solved
// and the columns to its right updated in the caller's number of bands of rows (by the block's size, not the
// threads), which the threads share out: the same operations, so the same block bit for bit, on any number.
#include <algorithm>

#include "common/thread_team.h"

namespace tvf {

// Rows lo .. hi split into `parts` bands of about equal cost, rowCost(r) >= 0: bounds[k] .. bounds[k+1].
template <typename Cost>
void splitRows(int lo, int hi, int parts, const Cost& rowCost, int* bounds) {
  double total = 0;
  for (int r = lo; r < hi; ++r) total += rowCost(r);
  bounds[0] = lo;
  double sum = 0;
  int r = lo;
  for (int k = 1; k < parts; ++k) {
    const double target = total * k / parts;
    while (r < hi && sum + rowCost(r) <= target) sum += rowCost(r++);
    bounds[k] = r;
  }
  bounds[parts] = hi;
}

// band(b, k) for the bands b = 0 .. bands - 1, those of part k of `parts` on thread k (common/thread_team.h),
// or all in order on this thread: which thread takes a band changes nothing in it.
template <typename Band>
void forBands(int bands, int parts, const Band& band) {
  parts = std::min(parts, bands);
  if (parts <= 1) {
    for (int b = 0; b < bands; ++b) band(b, 0);
    return;
  }
  ThreadTeam::shared().run(parts, [&](int k) {
    for (int b = partBegin(bands, k, parts); b < partBegin(bands, k + 1, parts); ++b) band(b, k);
  });
}

// 0, or the 1-based column of the block whose pivot was not positive. `bands` bands of rows on `parts`
// threads (one: all on this thread).
int factorBlockInBands(double* block, int nsrow, int nscol, int bands, int parts);

}  // namespace tvf
