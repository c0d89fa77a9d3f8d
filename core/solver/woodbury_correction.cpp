#include "solver/woodbury_correction.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

#include "common/simd_lanes.h"
#include "common/thread_team.h"
#include "solver/factor_columns.h"

namespace tvf {
namespace {

constexpr int kLineDoubles = 8;  // a 64-byte cache line
// The largest diagonal of K a held update may have (see prepare).
constexpr double kMostGrowth = 1e6;

// Up to this many columns of a supernode go together: each row of G they reach below is loaded and stored
// once for all of them.
constexpr int kBlock = 4;

// to[m] -= sum_c a[c] from[c][m] on [lo, hi): W columns' entries of L on one row, on every right-hand side
// whose path passes there. Four doubles a step, in two independent vector registers.
template <int W>
void subtractColumns(double* to, const double* const* from, const double* a, int lo, int hi) {
  Lanes2 scale[W];
  for (int c = 0; c < W; ++c) scale[c] = Lanes2{a[c], a[c]};
  int m = lo;
  for (; m + 4 <= hi; m += 4) {
    Lanes2 s0 = load2(to + m), s1 = load2(to + m + 2);
    for (int c = 0; c < W; ++c) {
      s0 -= scale[c] * load2(from[c] + m);
      s1 -= scale[c] * load2(from[c] + m + 2);
    }
    store2(to + m, s0);
    store2(to + m + 2, s1);
  }
  for (; m < hi; ++m) {
    double s = to[m];
    for (int c = 0; c < W; ++c) s -= a[c] * from[c][m];
    to[m] = s;
  }
}

void subtractColumns(int w, double* to, const double* const* from, const double* a, int lo, int hi) {
  switch (w) {
    case 4:
      return subtractColumns<4>(to, from, a, lo, hi);
    case 3:
      return subtractColumns<3>(to, from, a, lo, hi);
    case 2:
      return subtractColumns<2>(to, from, a, lo, hi);
    default:
      return subtractColumns<1>(to, from, a, lo, hi);
  }
}

// The same on two rows at once: each load of a column's right-hand sides serves both.
template <int W>
void subtractColumnsTwice(double* to0, double* to1, const double* const* from, const double* a0,
                          const double* a1, int lo, int hi) {
  Lanes2 scale0[W], scale1[W];
  for (int c = 0; c < W; ++c) {
    scale0[c] = Lanes2{a0[c], a0[c]};
    scale1[c] = Lanes2{a1[c], a1[c]};
  }
  int m = lo;
  for (; m + 2 <= hi; m += 2) {
    Lanes2 s0 = load2(to0 + m), s1 = load2(to1 + m);
    for (int c = 0; c < W; ++c) {
      const Lanes2 f = load2(from[c] + m);
      s0 -= scale0[c] * f;
      s1 -= scale1[c] * f;
    }
    store2(to0 + m, s0);
    store2(to1 + m, s1);
  }
  for (; m < hi; ++m) {
    double s0 = to0[m], s1 = to1[m];
    for (int c = 0; c < W; ++c) {
      s0 -= a0[c] * from[c][m];
      s1 -= a1[c] * from[c][m];
    }
    to0[m] = s0;
    to1[m] = s1;
  }
}

void subtractColumnsTwice(int w, double* to0, double* to1, const double* const* from, const double* a0,
                          const double* a1, int lo, int hi) {
  switch (w) {
    case 4:
      return subtractColumnsTwice<4>(to0, to1, from, a0, a1, lo, hi);
    case 3:
      return subtractColumnsTwice<3>(to0, to1, from, a0, a1, lo, hi);
    case 2:
      return subtractColumnsTwice<2>(to0, to1, from, a0, a1, lo, hi);
    default:
      return subtractColumnsTwice<1>(to0, to1, from, a0, a1, lo, hi);
  }
}

}  // namespace

bool WoodburyCorrection::prepare(const cholmod_factor& factor, const int* positions, const double* weights,
                                 int k, double* storage, size_t capacity, int* slot, int parts) {
  clear();
  if (k <= 0) return false;
  const FactorColumns L = factorColumns(factor);
  const int n = static_cast<int>(factor.n);
  // Q: the paths to the root, each walked until it meets one already taken. slot[j] is j's row in G; -1
  // outside Q, which the substitution checks for every row it reaches (a column's rows are its ancestors,
  // which a simplicial factor's exact pattern guarantees; anything else would write outside G).
  std::fill(slot, slot + n, -1);
  for (int m = 0; m < k; ++m)
    for (int j = positions[m]; j >= 0 && slot[j] < 0; j = parentColumn(L, j)) {
      slot[j] = 0;
      path_.push_back(j);
    }
  std::sort(path_.begin(), path_.end());
  const int rows = static_cast<int>(path_.size());
  stride_ = (k + kLineDoubles - 1) / kLineDoubles * kLineDoubles;
  if (static_cast<size_t>(rows) * static_cast<size_t>(stride_) > capacity) {
    path_.clear();
    return false;
  }
  for (int r = 0; r < rows; ++r) slot[path_[r]] = r;
  g_ = storage;
  k_ = k;
  // Right-hand side m is nonzero on the path from positions[m] only: with the positions ascending in a
  // postordered tree, the ones passing through a column are a range, widened from child to parent.
  low_.assign(rows, k);
  high_.assign(rows, -1);
  for (int m = 0; m < k; ++m) {
    const int r = slot[positions[m]];
    low_[r] = std::min(low_[r], m);
    high_[r] = std::max(high_[r], m);
    g_[static_cast<size_t>(r) * stride_ + m] = std::sqrt(weights[m]);
  }
  for (int r = 0; r < rows; ++r) {
    const int j = path_[r];
    if (L.nz[j] < 2 || high_[r] < 0) continue;
    const int parent = slot[L.i[L.p[j] + 1]];
    low_[parent] = std::min(low_[parent], low_[r]);
    high_[parent] = std::max(high_[parent], high_[r]);
  }
  // The right-hand sides in whole cache lines per part, so that no two threads write one line.
  const int lines = stride_ / kLineDoubles;
  parts = std::clamp(parts, 1, lines);
  std::atomic<bool> outside{false};
  ThreadTeam::shared().run(parts, [&](int t) {
    const int first = lines * t / parts * kLineDoubles,
              last = std::min(k, lines * (t + 1) / parts * kLineDoubles);
    int w = 1;
    for (int r = 0; r < rows && !outside.load(std::memory_order_relaxed); r += w) {
      // Columns j .. j + w - 1 of one supernode, all in Q (each is the next one's child). Every right-hand
      // side of the block passes through its last column, whose range is the widest.
      const int j = path_[r];
      w = 1;
      while (w < kBlock && r + w < rows && path_[r + w] == j + w && continuesSupernode(L, j + w - 1)) ++w;
      const int top = r + w - 1;
      const int lo = std::max(low_[top], first), hi = std::min(high_[top] + 1, last);
      if (lo >= hi) continue;
      const double* g[kBlock];
      double a[kBlock];
      // Within the block: column j + c's first entries below its diagonal are the block's next columns.
      for (int c = 0; c < w; ++c) {
        g[c] = g_ + static_cast<size_t>(r + c) * stride_;
        const double* inside = L.x + L.p[j + c] + 1;
        for (int q = 1; q < w - c; ++q)
          subtractColumns<1>(g_ + static_cast<size_t>(r + c + q) * stride_, &g[c], inside + q - 1, lo, hi);
      }
      // Below it: the rows of its last column, which every column of the block shares.
      const int l = j + w - 1;
      const int below = L.nz[l] - 1;
      const int* rowsBelow = L.i + L.p[l] + 1;
      const double* values[kBlock];
      for (int c = 0; c < w; ++c) values[c] = L.x + L.p[j + c] + (w - c);
      int q = 0;
      for (; q + 2 <= below; q += 2) {
        const int s0 = slot[rowsBelow[q]], s1 = slot[rowsBelow[q + 1]];
        if (s0 < 0 || s1 < 0) {
          outside.store(true, std::memory_order_relaxed);
          break;
        }
        double a1[kBlock];
        for (int c = 0; c < w; ++c) {
          a[c] = values[c][q];
          a1[c] = values[c][q + 1];
        }
        subtractColumnsTwice(w, g_ + static_cast<size_t>(s0) * stride_,
                             g_ + static_cast<size_t>(s1) * stride_, g, a, a1, lo, hi);
      }
      if (q < below) {
        const int s = slot[rowsBelow[q]];
        if (s < 0) {
          outside.store(true, std::memory_order_relaxed);
          continue;
        }
        for (int c = 0; c < w; ++c) a[c] = values[c][q];
        subtractColumns(w, g_ + static_cast<size_t>(s) * stride_, g, a, lo, hi);
      }
    }
  });
  if (outside) {
    clear();
    return false;
  }
  // K = I + G' D^-1 G, each part summing its rows (cut where the work, the square of each row's range, is
  // half done) into its own matrix.
  std::vector<double> work(static_cast<size_t>(rows) + 1, 0.0);
  for (int r = 0; r < rows; ++r) {
    const double width = high_[r] >= low_[r] ? high_[r] - low_[r] + 1 : 0;
    work[r + 1] = work[r] + width * width;
  }
  const int gramParts = rows > 4096 ? std::max(1, parts) : 1;
  std::vector<int> cuts(gramParts + 1, rows);
  cuts[0] = 0;
  for (int t = 1; t < gramParts; ++t)
    cuts[t] = static_cast<int>(std::lower_bound(work.begin(), work.end(), work[rows] * t / gramParts) -
                               work.begin());
  std::vector<double> grams(static_cast<size_t>(gramParts) * k * k, 0.0);
  ThreadTeam::shared().run(gramParts, [&](int t) {
    double* gram = grams.data() + static_cast<size_t>(t) * k * k;
    for (int r = cuts[t]; r < cuts[t + 1]; ++r) {
      if (high_[r] < low_[r]) continue;
      const double* gr = g_ + static_cast<size_t>(r) * stride_;
      const double inverseD = 1.0 / L.x[L.p[path_[r]]];
      for (int a = low_[r]; a <= high_[r]; ++a) {
        const double ga = gr[a] * inverseD;
        double* row = gram + static_cast<size_t>(a) * k;
        for (int b = a; b <= high_[r]; ++b) row[b] += ga * gr[b];
      }
    }
  });
  Eigen::MatrixXd K = Eigen::MatrixXd::Identity(k, k);
  for (int t = 0; t < gramParts; ++t)
    for (int a = 0; a < k; ++a)
      for (int b = a; b < k; ++b) K(b, a) += grams[(static_cast<size_t>(t) * k + a) * k + b];
  // The correction subtracts from u what the update takes out of it, and loses about eps x K's largest
  // diagonal (1 + w (A^-1)_rr) of u's precision to the difference (measured: 1.4 eps K against a fresh
  // factorization), where the update, backward stable, loses none of it. A 50-edge stroke of weight 1 (x the
  // mean diagonal) gives K 10-40 on the meshes here, so the page's default weight 1e4 ~1e5-4e5 (~1e-10);
  // past 1e6 (~3e-10, against the 1e-9 to which the page's field equals a fresh solve) the update goes into
  // the factor at once.
  if (K.diagonal().maxCoeff() > kMostGrowth) {
    clear();
    return false;
  }
  cholesky_.compute(K);  // reads the lower triangle
  if (cholesky_.info() != Eigen::Success) {
    clear();
    return false;
  }
  return true;
}

void WoodburyCorrection::correct(const cholmod_factor& factor, double* y) const {
  const FactorColumns L = factorColumns(factor);
  const int rows = static_cast<int>(path_.size());
  Eigen::VectorXd t = Eigen::VectorXd::Zero(k_);
  for (int r = 0; r < rows; ++r) {
    const int j = path_[r];
    const double* gr = g_ + static_cast<size_t>(r) * stride_;
    const double yj = y[j] / L.x[L.p[j]];
    for (int m = low_[r]; m <= high_[r]; ++m) t[m] += gr[m] * yj;
  }
  const Eigen::VectorXd s = cholesky_.solve(t);
  for (int r = 0; r < rows; ++r) {
    const double* gr = g_ + static_cast<size_t>(r) * stride_;
    double sum = 0;
    for (int m = low_[r]; m <= high_[r]; ++m) sum += gr[m] * s[m];
    y[path_[r]] -= sum;
  }
}

void WoodburyCorrection::clear() {
  if (g_) std::memset(g_, 0, path_.size() * static_cast<size_t>(stride_) * sizeof(double));
  g_ = nullptr;
  k_ = 0;
  path_.clear();
  low_.clear();
  high_.clear();
}

}  // namespace tvf
