#include "solver/forward_solution.h"

#include <algorithm>
#include <cmath>

#include "solver/factor_columns.h"

namespace tvf {
namespace {

// Each incremental substitution redoes Q from values rounded once more; a full one this often keeps y
// within a few ulps of a fresh substitution however long the session.
constexpr int kIncrementalBetweenFull = 64;
// A change of b on more rows than n / this is a new right-hand side (sources, vortices, boundary), not an
// edit's few rows: substituting in full is then cheaper than walking their paths.
constexpr int kChangedRowsFraction = 64;
// y carries the rounding of every right-hand side since its last full substitution, at their scale: once
// b has shrunk below the largest of them by more than this, y is redone in full (clearing a design would
// otherwise leave round-off of the old field where the new one is zero, amplified along a shifted kernel).
constexpr double kShrinkBeforeFull = 16;

}  // namespace

// Frees the vectors too: a factorization follows, and in wasm, whose heap never shrinks, vectors left between
// its large blocks would make it grow.
void ForwardSolution::invalidate() {
  clearPending();
  valid_ = false;
  std::vector<double>().swap(y_);
  std::vector<double>().swap(bLast_);
  std::vector<double>().swap(r_);
  std::vector<uint8_t>().swap(inSet_);
  std::vector<int>().swap(pending_);
  std::vector<int>().swap(changed_);
}

void ForwardSolution::clearPending() {
  for (const int j : pending_) {
    r_[j] = 0;
    inSet_[j] = 0;
  }
  pending_.clear();
}

// Adds the paths from `start` to the root to Q. Each column j joining Q is unchanged so far and y(j) is
// exact: its contribution y(j) e_j + (L - I)(:, j) y(j) moves into r, on rows that are its ancestors and so
// in Q too.
void ForwardSolution::addPaths(const cholmod_factor& factor, const int* start, int count) {
  const FactorColumns L = factorColumns(factor);
  for (int c = 0; c < count; ++c) {
    for (int j = start[c]; j >= 0 && !inSet_[j]; j = parentColumn(L, j)) {
      inSet_[j] = 1;
      pending_.push_back(j);
      const double yj = y_[j];
      r_[j] += yj;
      const int end = L.p[j] + L.nz[j];
      for (int p = L.p[j] + 1; p < end; ++p) r_[L.i[p]] += L.x[p] * yj;
    }
  }
}

void ForwardSolution::beforeUpdate(const cholmod_factor& L, const int* columns, int count) {
  if (valid_) addPaths(L, columns, count);
}

// Forward substitution on Q with the current L; children before parents, which ascending order is.
void ForwardSolution::substituteOnPending(const cholmod_factor& factor) {
  const FactorColumns L = factorColumns(factor);
  std::sort(pending_.begin(), pending_.end());
  for (const int j : pending_) {
    const double yj = r_[j];
    y_[j] = yj;
    r_[j] = 0;
    inSet_[j] = 0;
    const int end = L.p[j] + L.nz[j];
    for (int p = L.p[j] + 1; p < end; ++p) r_[L.i[p]] -= L.x[p] * yj;
  }
  pending_.clear();
}

bool ForwardSolution::substituteIncrementally(const cholmod_factor& L, const double* bPermuted) {
  const int n = static_cast<int>(L.n);
  if (!valid_ || static_cast<int>(y_.size()) != n || incremental_ >= kIncrementalBetweenFull) return false;
  changed_.clear();
  const int most = n / kChangedRowsFraction;
  double size = 0;
  for (int i = 0; i < n; ++i) {
    size = std::max(size, std::abs(bPermuted[i]));
    if (bPermuted[i] != bLast_[i]) {
      if (static_cast<int>(changed_.size()) >= most) return false;
      changed_.push_back(i);
    }
  }
  if (size * kShrinkBeforeFull < largestSinceFull_) return false;
  largestSinceFull_ = std::max(largestSinceFull_, size);
  addPaths(L, changed_.data(), static_cast<int>(changed_.size()));
  for (const int i : changed_) {
    r_[i] += bPermuted[i] - bLast_[i];
    bLast_[i] = bPermuted[i];
  }
  substituteOnPending(L);
  ++incremental_;
  ++incrementalTotal_;
  return true;
}

void ForwardSolution::setFull(const double* bPermuted, const double* y, int n) {
  clearPending();
  bLast_.assign(bPermuted, bPermuted + n);
  y_.assign(y, y + n);
  r_.assign(n, 0.0);
  inSet_.assign(n, 0);
  incremental_ = 0;
  largestSinceFull_ = 0;
  for (int i = 0; i < n; ++i) largestSinceFull_ = std::max(largestSinceFull_, std::abs(bPermuted[i]));
  valid_ = true;
}

}  // namespace tvf
