#include "cli/cholmod_baseline.h"

#include <algorithm>
#include <vector>

#include "cli/bench_timing.h"
#include "solver/cholmod_handles.h"

namespace tvf {

nlohmann::json cholmodBaseline(const SparseMatrix& A, int repeat) {
  repeat = std::max(repeat, 5);
  const SparseMatrix upper = upperTriangle(A);
  cholmod_sparse view = upperTriangleView(upper);
  CholmodCommon c;
  c->nmethods = 1;
  c->method[0].ordering = CHOLMOD_AMD;
  c->postorder = 1;
  c->supernodal = CHOLMOD_SIMPLICIAL;
  CholmodFactorPtr L(cholmod_analyze(&view, c.get()), {c.get()});
  if (!L || !cholmod_factorize(&view, L.get(), c.get()) || L->minor < L->n) return {};
  const int n = static_cast<int>(A.rows());
  CholmodDensePtr b(cholmod_ones(n, 1, CHOLMOD_REAL, c.get()), {c.get()});
  std::vector<double> solves, updates;
  for (int k = 0; k < repeat; ++k) {
    static_cast<double*>(b->x)[(k * 104729) % n] += 1.0;
    CholmodDensePtr x(nullptr, {c.get()});  // freed after the timing, as before the next solve
    solves.push_back(timeMs([&] { x.reset(cholmod_solve(CHOLMOD_A, L.get(), b.get(), c.get())); }));
  }
  for (int k = 0; k < repeat; ++k) {
    CholmodSparsePtr C(cholmod_allocate_sparse(n, 1, 1, 1, 1, 0, CHOLMOD_REAL, c.get()), {c.get()});
    static_cast<int*>(C->p)[0] = 0;
    static_cast<int*>(C->p)[1] = 1;
    static_cast<int*>(C->i)[0] = (k * 7919) % n;
    static_cast<double*>(C->x)[0] = 1.0;
    updates.push_back(timeMs([&] { cholmod_updown(1, C.get(), L.get(), c.get()); }));
  }
  int64_t nonzeros = 0;
  for (int j = 0; j < n; ++j) nonzeros += static_cast<const int*>(L->nz)[j];
  return {{"plainAmdSolveMs", median(solves)},
          {"plainAmdUpdateMs", median(updates)},
          {"plainAmdFactorNonzeros", nonzeros}};
}

}  // namespace tvf
