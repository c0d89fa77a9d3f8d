#include "solver/backward_substitution.h"

#include <algorithm>

#include "common/simd_lanes.h"
#include "common/thread_team.h"
#include "solver/factor_columns.h"

namespace tvf {
namespace {

// The K sums a_c(k) t(k), c < K, in one pass over t: the columns of a supernode share t.
template <int K>
void dotColumns(const double* const* a, const double* t, int m, double* sums) {
  Lanes2 acc[K];
  for (int c = 0; c < K; ++c) acc[c] = Lanes2{0, 0};
  int k = 0;
  for (; k + 2 <= m; k += 2) {
    const Lanes2 tk = load2(t + k);
    for (int c = 0; c < K; ++c) acc[c] += load2(a[c] + k) * tk;
  }
  for (int c = 0; c < K; ++c) sums[c] = acc[c][0] + acc[c][1];
  if (k < m) {
    for (int c = 0; c < K; ++c) sums[c] += a[c][k] * t[k];
  }
}

// sum a(k) x(rows(k)): a column on its own, where gathering first would only copy.
double dotGathered(const double* a, const int* rows, const double* x, int m) {
  double s0 = 0, s1 = 0;
  int k = 0;
  for (; k + 2 <= m; k += 2) {
    s0 += a[k] * x[rows[k]];
    s1 += a[k + 1] * x[rows[k + 1]];
  }
  if (k < m) s0 += a[k] * x[rows[k]];
  return s0 + s1;
}

}  // namespace

void BackwardSubstitution::invalidate() {
  std::vector<int>().swap(first_);
  partition_ = SubtreePartition();
  std::vector<std::vector<double>>().swap(gathered_);
}

void BackwardSubstitution::setParts(int parts) {
  parts_ = std::max(1, parts);
  invalidate();
}

// Columns j and j + 1 share a supernode when j's parent is j + 1 and j has exactly one row more (the
// diagonal): a column's rows below its diagonal are its ancestors, so then they are j + 1's rows.
void BackwardSubstitution::findSupernodes(const cholmod_factor& L) {
  const int n = static_cast<int>(L.n);
  const FactorColumns columns = factorColumns(L);
  first_.clear();
  int widest = 0;
  for (int j = 0; j < n; ++j) {
    if (j == 0 || !continuesSupernode(columns, j - 1)) first_.push_back(j);
    widest = std::max(widest, columns.nz[j] - 1);
  }
  first_.push_back(n);
  partitionSupernodes(L);
  gathered_.assign(std::max<size_t>(1, partition_.groups.size()), std::vector<double>(widest, 0.0));
}

// The supernodes' elimination tree: a supernode's parent holds the parent of its last column, the first row
// below its diagonal. Work: the supernode's entries of L, which its substitution reads once.
void BackwardSubstitution::partitionSupernodes(const cholmod_factor& L) {
  const int* Lp = static_cast<const int*>(L.p);
  const int* Li = static_cast<const int*>(L.i);
  const int* Lnz = static_cast<const int*>(L.nz);
  const int count = supernodeCount();
  std::vector<int> supernodeOf(L.n), parent(count, -1);
  std::vector<int64_t> work(count, 0);
  for (int s = 0; s < count; ++s)
    for (int c = first_[s]; c < first_[s + 1]; ++c) {
      supernodeOf[c] = s;
      work[s] += Lnz[c];
    }
  for (int s = 0; s < count; ++s) {
    const int l = first_[s + 1] - 1;
    if (Lnz[l] > 1) parent[s] = supernodeOf[Li[Lp[l] + 1]];
  }
  partition_ = partitionSubtrees(parent, work, parts_);
}

// x(c) = x(c) / D(c) - L(R, c)' t for the columns c = f..l of a supernode, whose rows R below it are final
// and gathered in t. These sums do not depend on one another: up to four columns at a time share each load
// of t, in the order the columns lie in memory.
void BackwardSubstitution::subtractBelow(const cholmod_factor& L, int f, int l, const double* t, int m,
                                         double* x) {
  const int* Lp = static_cast<const int*>(L.p);
  const double* Lx = static_cast<const double*>(L.x);
  const auto below = [&](int c) { return Lx + Lp[c] + 1 + (l - c); };
  for (int c = f; c <= l; c += 4) {
    const int count = std::min(4, l + 1 - c);
    const double* a[4];
    double sums[4];
    for (int q = 0; q < count; ++q) a[q] = below(c + q);
    switch (count) {
      case 4:
        dotColumns<4>(a, t, m, sums);
        break;
      case 3:
        dotColumns<3>(a, t, m, sums);
        break;
      case 2:
        dotColumns<2>(a, t, m, sums);
        break;
      default:
        dotColumns<1>(a, t, m, sums);
    }
    for (int q = 0; q < count; ++q) x[c + q] = x[c + q] / Lx[Lp[c + q]] - sums[q];
  }
}

// The supernodes in the order given (descending: each after its ancestors), with t as gather buffer.
void BackwardSubstitution::substitute(const cholmod_factor& L, const std::vector<int>& supernodes, double* t,
                                      double* x) const {
  const int* Lp = static_cast<const int*>(L.p);
  const int* Li = static_cast<const int*>(L.i);
  const int* Lnz = static_cast<const int*>(L.nz);
  const double* Lx = static_cast<const double*>(L.x);
  for (const int s : supernodes) {
    const int f = first_[s];
    const int l = first_[s + 1] - 1;
    const int m = Lnz[l] - 1;
    const int* below = Li + Lp[l] + 1;
    if (f == l) {
      const double* column = Lx + Lp[l];
      x[l] = x[l] / column[0] - dotGathered(column + 1, below, x, m);
      continue;
    }
    for (int k = 0; k < m; ++k) t[k] = x[below[k]];
    subtractBelow(L, f, l, t, m, x);
    // The triangle within the supernode, last column first: column c's rows c + 1 .. l are final by then.
    for (int c = l; c >= f; --c) {
      const double* inside = Lx + Lp[c] + 1;
      double sum;
      dotColumns<1>(&inside, x + c + 1, l - c, &sum);
      x[c] -= sum;
    }
  }
}

void BackwardSubstitution::prepare(const cholmod_factor& L) {
  if (first_.empty() || first_.back() != static_cast<int>(L.n)) findSupernodes(L);
}

void BackwardSubstitution::solve(const cholmod_factor& L, const double* y, double* x) {
  const int n = static_cast<int>(L.n);
  prepare(L);
  if (x != y) std::copy(y, y + n, x);
  substitute(L, partition_.top, gathered_[0].data(), x);
  const std::vector<std::vector<int>>& groups = partition_.groups;
  if (groups.empty()) return;
  ThreadTeam::shared().run(static_cast<int>(groups.size()),
                           [&](int k) { substitute(L, groups[k], gathered_[k].data(), x); });
}

}  // namespace tvf
