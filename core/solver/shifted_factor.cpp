#include "solver/shifted_factor.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "common/input_error.h"

namespace tvf {
namespace {

// The kernel of M is made definite by a diagonal shift this small relative to the mean diagonal; it is
// raised only if CHOLMOD still finds a non-positive pivot.
constexpr double kInitialShift = 1e-9;
constexpr double kMaxShift = 1e-4;
// A downdate that removes weight w (relative to the mean diagonal) leaves round-off of about eps * w in the
// pivots it passes through: removing a 1e20 weight leaves nothing of the original pivot (all NaN), removing
// 1e8 leaves 1e-8. The weights taken out by downdates since the last factorization are summed; a downdate
// that would push the sum past the budget refactors instead. With a kernel shift the system is as badly
// conditioned as the shift is small, and that round-off reaches the field amplified: the budget keeps it
// within ~1e-12 of a fresh factor. Without one (every component closed and of genus 0) the round-off stays
// what it is, and the solve after downdates checks its backward error anyway (solvesToRoundOff): there a
// stroke's rows, which weigh 5e3-1e4 mean diagonals, would refactor at every second undo under the small
// budget (bunny00 in the page: 150-270 ms instead of 25-30 ms; armadillo-sub2: seconds), and the large one
// lets about a hundred strokes be undone between factorizations, the factor within ~1e-10 of a fresh one.
constexpr double kDowndateBudgetShifted = 1e4;
constexpr double kDowndateBudget = 1e6;
// Backward error ||b - A x|| / (||A|| ||x|| + ||b||) (infinity norms) of a solve after downdates beyond
// which the factor is considered spoilt: a downdated factor is that of A + E with ||E|| ~ eps * (weight
// removed), and this is ||E x|| / ||A|| ||x||; a fresh LDL' gives ~1e-16.
constexpr double kDowndatedBackwardErrorTolerance = 1e-10;

// Largest absolute row sum of the symmetric matrix whose upper triangle is `upper`.
double infinityNorm(const SparseMatrix& upper) {
  std::vector<double> sums(static_cast<size_t>(upper.rows()), 0.0);
  for (int j = 0; j < upper.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(upper, j); it; ++it) {
      sums[j] += std::abs(it.value());
      if (it.row() != j) sums[it.row()] += std::abs(it.value());
    }
  return sums.empty() ? 0.0 : *std::max_element(sums.begin(), sums.end());
}

double physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
  return pages > 0 && pageSize > 0 ? static_cast<double>(pages) * static_cast<double>(pageSize) : 0.0;
}

}  // namespace

SparseMatrix plusDiagonal(const SparseMatrix& base, const DiagonalTerms& terms) {
  std::vector<Eigen::Triplet<double, int>> diag;
  for (size_t k = 0; k < terms.rows.size(); ++k)
    diag.emplace_back(terms.rows[k], terms.rows[k], terms.weights[k]);
  SparseMatrix D(base.rows(), base.cols());
  D.setFromTriplets(diag.begin(), diag.end());
  return base + D;
}

ShiftedFactor::ShiftedFactor(std::vector<uint8_t> kernelEdges, FillOrdering ordering)
    : kernelEdges_(std::move(kernelEdges)), system_(ordering) {
  anyKernel_ = std::any_of(kernelEdges_.begin(), kernelEdges_.end(), [](uint8_t k) { return k != 0; });
}

void ShiftedFactor::setOrdering(FillOrdering ordering) {
  system_.setOrdering(ordering);
  stale_ = true;
}

KeptOrdering ShiftedFactor::keptOrdering() const {
  return system_.keptOrdering();
}

bool ShiftedFactor::adoptOrdering(KeptOrdering kept) {
  return system_.adoptOrdering(std::move(kept));
}

void ShiftedFactor::setKeepSymbolic(bool keep) {
  system_.setKeepSymbolic(keep);
}

bool ShiftedFactor::keptOrderingIsNew() const {
  return system_.keptOrderingIsNew();
}

void ShiftedFactor::setEdgeGraph(std::vector<int32_t> edgeVertices, int32_t numVertices) {
  system_.setEdgeGraph(std::move(edgeVertices), numVertices);
  stale_ = true;
}

void ShiftedFactor::setThreads(int threads) {
  system_.setThreads(threads);
  stale_ = true;
}

int ShiftedFactor::threads() const {
  return system_.threads();
}

void ShiftedFactor::setMemoryLimit(double bytes) {
  memoryLimit_ = bytes;
}

double ShiftedFactor::memoryLimit() const {
  return memoryLimit_;
}

bool ShiftedFactor::current() const {
  return !stale_ && system_.factored();
}

void ShiftedFactor::invalidate() {
  stale_ = true;
}

void ShiftedFactor::release() {
  system_.release();
  stale_ = true;
}

std::vector<double> ShiftedFactor::shiftedDiagonal(double scale, const DiagonalTerms& terms) const {
  std::vector<double> diagonal(kernelEdges_.size(), 0.0);
  for (size_t e = 0; e < kernelEdges_.size(); ++e)
    if (shiftEverywhere_ || kernelEdges_[e]) diagonal[e] = shift_ * scale;
  for (size_t k = 0; k < terms.rows.size(); ++k) diagonal[terms.rows[k]] += terms.weights[k];
  return diagonal;
}

void ShiftedFactor::factor(const SparseMatrix& base, double scale, const DiagonalTerms& terms) {
  int retries = 0;
  shiftEverywhere_ = false;
  shift_ = anyKernel_ ? kInitialShift : 0.0;
  termSums_ = Eigen::VectorXd();  // scratch of the checks: not kept between the factorization's large blocks
  system_.setMemoryLimit(memoryLimit_ > 0 ? memoryLimit_ : physicalMemoryBytes());
  while (!system_.factorUpper(base, shiftedDiagonal(scale, terms))) {
    // Numerically singular despite the topology (e.g. a near-kernel on a badly shaped closed mesh).
    ++retries;
    shift_ = shiftEverywhere_ ? shift_ * 100 : kInitialShift;
    shiftEverywhere_ = true;
    if (shift_ > kMaxShift)
      throw InputError("the system could not be factored even with a diagonal shift of " +
                       std::to_string(shift_ / 100) + " (is the mesh badly shaped?)");
  }
  const FactorTimings& t = system_.timings();
  report_.analyzeMs = t.analyzeMs;
  report_.analysisReused = t.analysisReused;
  report_.symbolicReused = t.symbolicReused;
  report_.factorMs = t.factorMs + t.convertMs;
  report_.convertMs = t.convertMs;
  report_.dissectionMs = t.dissectionMs;
  report_.factorThreads = t.factorThreads;
  report_.factorGroups = t.factorGroups;
  report_.singleThreadWhy = t.singleThreadWhy;
  report_.factorNonzeros = system_.factorNonzeros();
  ++report_.factorizations;
  report_.kernelShift = shift_;
  char text[240];
  if (shift_ == 0)
    std::snprintf(text, sizeof text, "none needed: every component is closed and of genus 0");
  else
    std::snprintf(text, sizeof text,
                  "diagonal shift %.0e x mean diagonal on the edges of %s, then one step of iterative "
                  "refinement against the unshifted matrix; %d retries",
                  shift_, shiftEverywhere_ ? "every component" : "components with handles or boundary",
                  retries);
  report_.kernelHandling = text;
  report_.factorKind = system_.description();
  stale_ = false;
  downdateLoad_ = 0;
  updatedSinceFactor_ = false;
  downdatedSinceCheck_ = false;
  baseNorm_ = infinityNorm(base);
}

void ShiftedFactor::update(const DiagonalTerms& change, double scale, bool downdate) {
  if (stale_ || change.rows.empty()) return;  // the next factorization includes the change
  if (downdate) {
    double largest = 0;
    for (const double w : change.weights) largest = std::max(largest, w / scale);
    if (downdateLoad_ + largest > (shift_ > 0 ? kDowndateBudgetShifted : kDowndateBudget)) {
      stale_ = true;  // refactor at the next solve instead of downdating away the precision
      return;
    }
    downdateLoad_ += largest;
    downdatedSinceCheck_ = true;
  }
  updatedSinceFactor_ = true;
  const auto start = std::chrono::steady_clock::now();
  if (deferUpdates_ && !downdate)
    system_.deferUpdate(change.rows, change.weights);
  else
    system_.updateDiagonal(change.rows, change.weights, downdate);
  updateMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void ShiftedFactor::setDeferredUpdates(bool defer) {
  deferUpdates_ = defer;
  if (!defer) applyDeferred();
}

void ShiftedFactor::applyDeferred() {
  if (!system_.hasDeferred()) return;
  const auto start = std::chrono::steady_clock::now();
  try {
    system_.applyDeferred();
  } catch (const std::exception&) {
    stale_ = true;  // a failed update leaves the factor unusable: the next solve refactors
  }
  deferredUpdateMs_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The shift biases the solution by O(shift / smallest nonzero eigenvalue), and fully for fields that only
// constraints pin down (a constant field on a free-boundary patch lies in the kernel of M). One step of
// iterative refinement against the unshifted matrix cuts that to O(shift^2) for one more solve; kernel
// components the design leaves free stay at the minimum-norm choice.
void ShiftedFactor::refineAgainstUnshiftedSystem(const SparseMatrix& base, const DiagonalTerms& terms,
                                                 const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Eigen::VectorXd residual = b - base.selfadjointView<Eigen::Upper>() * x;
  for (size_t k = 0; k < terms.rows.size(); ++k)
    residual[terms.rows[k]] -= terms.weights[k] * x[terms.rows[k]];
  Eigen::VectorXd correction;
  system_.solveOnce(residual, correction);
  x += correction;
}

// The matrix the factor holds (base + shift + terms) times x.
Eigen::VectorXd ShiftedFactor::factoredProduct(const SparseMatrix& base, double scale,
                                               const DiagonalTerms& terms, const Eigen::VectorXd& x) const {
  Eigen::VectorXd y = base.selfadjointView<Eigen::Upper>() * x;
  if (shift_ > 0)
    for (int32_t e = 0; e < static_cast<int32_t>(kernelEdges_.size()); ++e)
      if (shiftEverywhere_ || kernelEdges_[e]) y[e] += shift_ * scale * x[e];
  for (size_t k = 0; k < terms.rows.size(); ++k) y[terms.rows[k]] += terms.weights[k] * x[terms.rows[k]];
  return y;
}

// The infinity norm of what the factor holds, bounded by its parts' (the terms summed per row).
double ShiftedFactor::factoredNorm(double scale, const DiagonalTerms& terms) {
  termSums_.resize(static_cast<Eigen::Index>(kernelEdges_.size()));
  double largestTerm = 0;
  for (size_t k = 0; k < terms.rows.size(); ++k) termSums_[terms.rows[k]] = 0;
  for (size_t k = 0; k < terms.rows.size(); ++k)
    largestTerm = std::max(largestTerm, termSums_[terms.rows[k]] += terms.weights[k]);
  return baseNorm_ + shift_ * scale + largestTerm;
}

// Whether a solution x of the updated factor solves the factored matrix to round-off.
bool ShiftedFactor::solvesToRoundOff(const SparseMatrix& base, double scale, const DiagonalTerms& terms,
                                     const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  const Eigen::VectorXd residual = b - factoredProduct(base, scale, terms, x);
  const double error = residual.lpNorm<Eigen::Infinity>();
  const double size = factoredNorm(scale, terms) * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>();
  return std::isfinite(error) && error <= kDowndatedBackwardErrorTolerance * size;
}

// Updates that add positive terms to a positive definite factor are backward stable (Gill, Golub, Murray
// and Saunders, Method C1), so only a solve after downdates is checked, once: a factor that passed stays
// good while only updates follow.
void ShiftedFactor::solve(const SparseMatrix& base, double scale, const DiagonalTerms& terms,
                          const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  system_.solve(b, x);
  if (updatedSinceFactor_) {
    const bool spoilt =
        !x.allFinite() || (downdatedSinceCheck_ && !solvesToRoundOff(base, scale, terms, b, x));
    if (spoilt) {
      ++precisionRefactors_;
      factor(base, scale, terms);
      system_.solve(b, x);
    }
    downdatedSinceCheck_ = false;
  }
  if (shift_ > 0 && x.allFinite()) refineAgainstUnshiftedSystem(base, terms, b, x);
}

const FactorReport& ShiftedFactor::report() const {
  return report_;
}

double ShiftedFactor::lastUpdateMs() const {
  return updateMs_;
}

double ShiftedFactor::lastDeferredUpdateMs() const {
  return deferredUpdateMs_;
}

int64_t ShiftedFactor::incrementalSolves() const {
  return system_.incrementalSolves();
}

int64_t ShiftedFactor::supernodalSolves() const {
  return system_.supernodalSolves();
}

int32_t ShiftedFactor::precisionRefactors() const {
  return precisionRefactors_;
}

}  // namespace tvf
