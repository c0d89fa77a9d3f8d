#include "solver/permuted_triangle.h"

#include <algorithm>
#include <exception>
#include <functional>
#include <utility>

#include "common/thread_team.h"
#include "solver/cholmod_handles.h"
#include "solver/dense_cholesky.h"

namespace tvf {

// Each part counts, then places, the entries of its share of A's columns (its own counts per column of the
// result), so that a column's entries come in the order of A's columns however many parts there are.
PermutedTriangle permutedTriangle(const cholmod_sparse& A, const std::vector<int>& inverse, Triangle which,
                                  bool values, int parts) {
  const int n = static_cast<int>(A.ncol);
  const int* Ap = static_cast<const int*>(A.p);
  const int* Ai = static_cast<const int*>(A.i);
  const double* Ax = static_cast<const double*>(A.x);
  const bool lower = which == Triangle::Lower;
  parts = std::clamp(parts, 1, ThreadTeam::maxParts());
  if (parts > 1) {
    try {
      ThreadTeam::shared();
    } catch (const std::exception&) {
      parts = 1;  // the helpers could not start: the same arrays, on this thread
    }
  }
  std::vector<int> bounds(parts + 1);
  splitRows(
      0, n, parts, [&](int j) { return static_cast<double>(Ap[j + 1] - Ap[j]); }, bounds.data());
  std::vector<std::vector<int>> next(parts, std::vector<int>(n + 1, 0));
  // One part runs here without the team, which may be what could not start.
  const auto run = [parts](const std::function<void(int)>& task) {
    if (parts == 1) return task(0);
    ThreadTeam::shared().run(parts, task);
  };
  run([&](int t) {
    int* count = next[t].data();
    for (int j = bounds[t]; j < bounds[t + 1]; ++j)
      for (int q = Ap[j]; q < Ap[j + 1]; ++q) {
        const int a = inverse[Ai[q]], b = inverse[j];
        ++count[lower ? std::min(a, b) : std::max(a, b)];
      }
  });
  PermutedTriangle T;
  T.p.assign(n + 1, 0);
  int at = 0;
  for (int k = 0; k < n; ++k) {
    T.p[k] = at;
    for (int t = 0; t < parts; ++t) at += std::exchange(next[t][k], at);
  }
  T.p[n] = at;
  T.i.resize(at);
  if (values) T.x.resize(at);
  run([&](int t) {
    int* place = next[t].data();
    for (int j = bounds[t]; j < bounds[t + 1]; ++j)
      for (int q = Ap[j]; q < Ap[j + 1]; ++q) {
        const int a = inverse[Ai[q]], b = inverse[j];
        const int slot = place[lower ? std::min(a, b) : std::max(a, b)]++;
        T.i[slot] = lower ? std::max(a, b) : std::min(a, b);
        if (values) T.x[slot] = Ax[q];
      }
  });
  return T;
}

cholmod_sparse patternView(PermutedTriangle& t, Triangle which) {
  return compressedView(t.p.size() - 1, t.i.size(), t.p.data(), t.i.data(), nullptr,
                        which == Triangle::Upper ? 1 : -1, false);
}

}  // namespace tvf
