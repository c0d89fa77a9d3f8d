#include "cli/cholmod_baseline.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "solver/cholmod_handles.h"

namespace tvf {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

}  // namespace

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
    const auto start = std::chrono::steady_clock::now();
    CholmodDensePtr x(cholmod_solve(CHOLMOD_A, L.get(), b.get(), c.get()), {c.get()});
    solves.push_back(msSince(start));
  }
  for (int k = 0; k < repeat; ++k) {
    CholmodSparsePtr C(cholmod_allocate_sparse(n, 1, 1, 1, 1, 0, CHOLMOD_REAL, c.get()), {c.get()});
    static_cast<int*>(C->p)[0] = 0;
    static_cast<int*>(C->p)[1] = 1;
    static_cast<int*>(C->i)[0] = (k * 7919) % n;
    static_cast<double*>(C->x)[0] = 1.0;
    const auto start = std::chrono::steady_clock::now();
    cholmod_updown(1, C.get(), L.get(), c.get());
    updates.push_back(msSince(start));
  }
  int64_t nonzeros = 0;
  for (int j = 0; j < n; ++j) nonzeros += static_cast<const int*>(L->nz)[j];
  return {{"plainAmdSolveMs", median(solves)},
          {"plainAmdUpdateMs", median(updates)},
          {"plainAmdFactorNonzeros", nonzeros}};
}

}  // namespace tvf
