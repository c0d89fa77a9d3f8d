#include "solver/dense_cholesky.h"

#include <algorithm>
#include <vector>

#ifndef __EMSCRIPTEN__
#include <dlfcn.h>
#endif

#include "common/thread_team.h"
#include "solver/dense_kernels.h"

namespace tvf {
namespace {

// Columns per panel: wide enough that the updates are matrix products, narrow enough that the panel's own
// factorization, on one thread, stays small.
constexpr int kPanel = 64;

// Rows [r0, r1) of the columns [k1, nscol) to the right of panel [k0, k1): minus the panel's product with its
// rows [k1, nscol), the lower triangle only where the rows are the diagonal block's.
void updateRows(double* b, int ld, int nscol, int k0, int k1, int r0, int r1) {
  const double* panel = b + static_cast<size_t>(k0) * ld;
  const int a = std::max(r0, k1);
  const int diagEnd = std::min(r1, nscol);
  if (a < diagEnd) {  // rows in the diagonal block: the square part before them, then their own triangle
    blas::gemmNTSubtract(diagEnd - a, a - k1, k1 - k0, panel + a, ld, panel + k1, ld,
                         b + a + static_cast<size_t>(k1) * ld, ld);
    blas::syrkLowerSubtract(diagEnd - a, k1 - k0, panel + a, ld, b + a + static_cast<size_t>(a) * ld, ld);
  }
  const int below = std::max(a, nscol);
  if (below < r1)
    blas::gemmNTSubtract(r1 - below, nscol - k1, k1 - k0, panel + below, ld, panel + k1, ld,
                         b + below + static_cast<size_t>(k1) * ld, ld);
}

#ifndef __EMSCRIPTEN__
using SetThreads = void (*)(int);
using GetThreads = int (*)();

SetThreads openblasSetThreads() {
  return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
}
#endif

}  // namespace

namespace blas {

BlasOnCallingThread::BlasOnCallingThread() {
#ifndef __EMSCRIPTEN__
  const auto get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  const SetThreads set = openblasSetThreads();
  if (!get || !set) return;
  restore_ = get();
  if (restore_ > 1) set(1);
#endif
}

BlasOnCallingThread::~BlasOnCallingThread() {
#ifndef __EMSCRIPTEN__
  if (restore_ > 1) openblasSetThreads()(restore_);
#endif
}

}  // namespace blas

int factorBlockInBands(double* block, int nsrow, int nscol, int bands, int parts) {
  std::vector<int> bounds(bands + 1);
  for (int k0 = 0; k0 < nscol; k0 += kPanel) {
    const int k1 = std::min(nscol, k0 + kPanel), width = k1 - k0;
    double* diagonal = block + k0 + static_cast<size_t>(k0) * nsrow;
    const int info = blas::potrfLower(width, diagonal, nsrow);
    if (info != 0) return k0 + info;
    if (k1 == nsrow) break;
    splitRows(
        k1, nsrow, bands, [](int) { return 1.0; }, bounds.data());
    forBands(bands, parts, [&](int b, int) {
      blas::trsmRightLowerTransposed(bounds[b + 1] - bounds[b], width, diagonal, nsrow,
                                     block + bounds[b] + static_cast<size_t>(k0) * nsrow, nsrow);
    });
    if (k1 == nscol) break;
    splitRows(
        k1, nsrow, bands, [&](int r) { return static_cast<double>(std::min(r + 1, nscol) - k1); },
        bounds.data());
    forBands(bands, parts,
             [&](int b, int) { updateRows(block, nsrow, nscol, k0, k1, bounds[b], bounds[b + 1]); });
  }
  return 0;
}

}  // namespace tvf
