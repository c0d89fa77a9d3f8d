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

// to[r][m] -= sum_c a[r][c] from[c][m] on [lo, hi), for R rows of G and W columns of a supernode: the
// forward substitution's step, on every right-hand side whose path passes there. Each load of a column's
// right-hand sides serves all R rows.
template <int R, int W>
void subtractColumns(double* const* to, const double* const* from, const double* const* a, int lo, int hi) {
  Lanes2 scale[R][W];
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < W; ++c) scale[r][c] = Lanes2{a[r][c], a[r][c]};
  int m = lo;
  for (; m + 2 <= hi; m += 2) {
    Lanes2 s[R];
    for (int r = 0; r < R; ++r) s[r] = load2(to[r] + m);
    for (int c = 0; c < W; ++c) {
      const Lanes2 f = load2(from[c] + m);
      for (int r = 0; r < R; ++r) s[r] -= scale[r][c] * f;
    }
    for (int r = 0; r < R; ++r) store2(to[r] + m, s[r]);
  }
  for (; m < hi; ++m)
    for (int r = 0; r < R; ++r) {
      double s = to[r][m];
      for (int c = 0; c < W; ++c) s -= a[r][c] * from[c][m];
      to[r][m] = s;
    }
}

template <int R>
void subtractColumns(int w, double* const* to, const double* const* from, const double* const* a, int lo,
                     int hi) {
  switch (w) {
    case 4:
      return subtractColumns<R, 4>(to, from, a, lo, hi);
    case 3:
      return subtractColumns<R, 3>(to, from, a, lo, hi);
    case 2:
      return subtractColumns<R, 2>(to, from, a, lo, hi);
    default:
      return subtractColumns<R, 1>(to, from, a, lo, hi);
  }
}

}  // namespace

bool WoodburyCorrection::prepare(const cholmod_factor& factor, const int* positions, const double* weights,
                                 int k, double* storage, size_t capacity, int* slot, int parts) {
  clear();
  if (k <= 0) return false;
  const FactorColumns L = factorColumns(factor);
  if (!collectPaths(L, static_cast<int>(factor.n), positions, k, capacity, slot)) return false;
  g_ = storage;
  k_ = k;
  spreadRanges(L, positions, weights, slot);
  if (!substituteForward(L, slot, parts)) {
    clear();
    return false;
  }
  const Eigen::MatrixXd K = identityPlusGram(L, parts);
  // The correction subtracts from u what the update takes out of it, and loses about eps x K's largest
  // diagonal (1 + w (A^-1)_rr) of u's precision to the difference (measured: 1.4 eps K against a fresh
  // factorization), where the update, backward stable, loses none of it. A 50-edge stroke of weight 1 (x the
  // mean diagonal) gives K 10-40 on the meshes here, and K - I grows with the weight, so the page's default
  // weight 1e4 comes to ~1e5-4e5 (~1e-10); past 1e6 (~3e-10, against the 1e-9 to which the page's field
  // equals a fresh solve) the update goes into the factor at once.
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

// Q: the paths to the root, each walked until it meets one already taken, ascending; slot[j] is j's row in
// G, -1 outside Q. False when G would not fit in `capacity` doubles.
bool WoodburyCorrection::collectPaths(const FactorColumns& L, int n, const int* positions, int k,
                                      size_t capacity, int* slot) {
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
  return true;
}

// G's starting values sqrt(w_m) e_{positions[m]}, and the range of right-hand sides on each row of Q.
// Right-hand side m is nonzero on the path from positions[m] only: with the positions ascending in a
// postordered tree, the ones passing through a column are a range, widened from child to parent.
void WoodburyCorrection::spreadRanges(const FactorColumns& L, const int* positions, const double* weights,
                                      const int* slot) {
  const int rows = static_cast<int>(path_.size());
  low_.assign(rows, k_);
  high_.assign(rows, -1);
  for (int m = 0; m < k_; ++m) {
    const int r = slot[positions[m]];
    low_[r] = std::min(low_[r], m);
    high_[r] = std::max(high_[r], m);
    g_[static_cast<size_t>(r) * stride_ + m] = std::sqrt(weights[m]);
  }
  for (int r = 0; r < rows; ++r) {
    const int parent = parentColumn(L, path_[r]);
    if (parent < 0 || high_[r] < 0) continue;
    const int up = slot[parent];
    low_[up] = std::min(low_[up], low_[r]);
    high_[up] = std::max(high_[up], high_[r]);
  }
}

// G = L^-1 G on Q, children before parents, the right-hand sides split between the parts in whole cache
// lines (no two threads write one line). False when a column has a row outside Q: a column's rows are its
// ancestors in a simplicial factor's exact pattern, and anything else would write outside G.
bool WoodburyCorrection::substituteForward(const FactorColumns& L, const int* slot, int parts) {
  const int rows = static_cast<int>(path_.size());
  const int lines = stride_ / kLineDoubles;
  parts = std::clamp(parts, 1, lines);
  std::atomic<bool> outside{false};
  const auto row = [&](int r) { return g_ + static_cast<size_t>(r) * stride_; };
  ThreadTeam::shared().run(parts, [&](int t) {
    const int first = lines * t / parts * kLineDoubles,
              last = std::min(k_, lines * (t + 1) / parts * kLineDoubles);
    int w = 1;
    for (int r = 0; r < rows && !outside.load(std::memory_order_relaxed); r += w) {
      // Columns j .. j + w - 1 of one supernode, all in Q (each is the next one's child). Every right-hand
      // side of the block passes through its last column, whose range is the widest.
      const int j = path_[r];
      w = 1;
      while (w < kBlock && r + w < rows && path_[r + w] == j + w && continuesSupernode(L, j + w - 1)) ++w;
      const int lo = std::max(low_[r + w - 1], first), hi = std::min(high_[r + w - 1] + 1, last);
      if (lo >= hi) continue;
      const double* g[kBlock];
      // Within the block: column j + c's first entries below its diagonal are the block's next columns.
      for (int c = 0; c < w; ++c) {
        g[c] = row(r + c);
        const double* inside = L.x + L.p[j + c] + 1;
        for (int q = 1; q < w - c; ++q) {
          double* to = row(r + c + q);
          const double* a = inside + q - 1;
          subtractColumns<1, 1>(&to, &g[c], &a, lo, hi);
        }
      }
      // Below it: the rows of its last column, which every column of the block shares, two at a time.
      const int l = j + w - 1;
      const int below = L.nz[l] - 1;
      const int* rowsBelow = L.i + L.p[l] + 1;
      const double* values[kBlock];
      for (int c = 0; c < w; ++c) values[c] = L.x + L.p[j + c] + (w - c);
      for (int q = 0; q < below; q += 2) {
        const int pair = std::min(2, below - q);
        double* to[2];
        double a[2][kBlock];
        const double* scales[2] = {a[0], a[1]};
        for (int h = 0; h < pair; ++h) {
          const int s = slot[rowsBelow[q + h]];
          if (s < 0) {
            outside.store(true, std::memory_order_relaxed);
            return;
          }
          to[h] = row(s);
          for (int c = 0; c < w; ++c) a[h][c] = values[c][q + h];
        }
        if (pair == 2)
          subtractColumns<2>(w, to, g, scales, lo, hi);
        else
          subtractColumns<1>(w, to, g, scales, lo, hi);
      }
    }
  });
  return !outside;
}

// K = I + G' D^-1 G (its lower triangle), each chunk of rows (cut where the work, the square of each row's
// range, is even) summed into its own matrix, the chunks then added in order. The chunks are the same
// whatever the threads that share them out: K is the same bit for bit on any number of threads.
Eigen::MatrixXd WoodburyCorrection::identityPlusGram(const FactorColumns& L, int parts) const {
  constexpr int kGramChunks = 4;
  const int rows = static_cast<int>(path_.size()), k = k_;
  std::vector<double> work(static_cast<size_t>(rows) + 1, 0.0);
  for (int r = 0; r < rows; ++r) {
    const double width = high_[r] >= low_[r] ? high_[r] - low_[r] + 1 : 0;
    work[r + 1] = work[r] + width * width;
  }
  const int gramParts = rows > 4096 ? kGramChunks : 1;
  parts = std::clamp(parts, 1, gramParts);
  std::vector<int> cuts(gramParts + 1, rows);
  cuts[0] = 0;
  for (int t = 1; t < gramParts; ++t)
    cuts[t] = static_cast<int>(std::lower_bound(work.begin(), work.end(), work[rows] * t / gramParts) -
                               work.begin());
  std::vector<double> grams(static_cast<size_t>(gramParts) * k * k, 0.0);
  const auto sumChunk = [&](int t) {
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
  };
  ThreadTeam::shared().run(parts, [&](int k) {
    for (int t = partBegin(gramParts, k, parts); t < partBegin(gramParts, k + 1, parts); ++t) sumChunk(t);
  });
  Eigen::MatrixXd K = Eigen::MatrixXd::Identity(k, k);
  for (int t = 0; t < gramParts; ++t)
    for (int a = 0; a < k; ++a)
      for (int b = a; b < k; ++b) K(b, a) += grams[(static_cast<size_t>(t) * k + a) * k + b];
  return K;
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
