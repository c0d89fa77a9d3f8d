// SPDX-License-Identifier: GPL-2.0-or-later
#include "solver/spd_solve.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "solver/cholmod_handles.h"
#include "solver/dense_kernels.h"
#include "solver/supernodal_cholesky.h"
#include "solver/supernodal_solve.h"
#include "solver/symbolic_analysis.h"

namespace tvf {

struct SpdFactor::Impl {
  CholmodCommon common;
  CholmodFactorPtr factor{nullptr, {common.get()}};
  std::vector<int> outer, inner;  // the pattern the analysis was made for
  size_t n = 0;
  std::vector<int> ordering;  // given, or empty
  KeptSymbolic symbolic;      // given with the ordering, or empty
  bool ok = false, reused = false;

  bool samePattern(const SparseMatrix& upper) const {
    return factor && static_cast<size_t>(upper.rows()) == n &&
           std::equal(outer.begin(), outer.end(), upper.outerIndexPtr(), upper.outerIndexPtr() + n + 1) &&
           static_cast<size_t>(upper.nonZeros()) == inner.size() &&
           std::equal(inner.begin(), inner.end(), upper.innerIndexPtr());
  }

  void factorize(const SparseMatrix& upper) {
    ok = reused = false;
    if (upper.cols() != upper.rows() || !upper.isCompressed()) return;
    cholmod_sparse A = upperTriangleView(upper);
    cholmod_common& c = *common.get();
    reused = samePattern(upper);
    PermutedTriangle lower;  // the lower triangle of P A P', made by the analysis of a given ordering
    if (!reused) {
      n = static_cast<size_t>(upper.rows());
      if (n == 0) return void(ok = true);
      outer.assign(upper.outerIndexPtr(), upper.outerIndexPtr() + n + 1);
      inner.assign(upper.innerIndexPtr(), upper.innerIndexPtr() + upper.nonZeros());
      // A given symbolic factor is tried for the first pattern only; where it does not fit, an analysis.
      cholmod_factor* made = ordering.size() == n && !symbolic.empty()
                                 ? symbolicFromKept(A, ordering, symbolic, 1, c, lower)
                                 : nullptr;
      symbolic = KeptSymbolic();
      if (!made)
        made = ordering.size() == n ? analyzeOrdering(A, ordering, 1, c, lower) : cholmod_analyze(&A, &c);
      factor.reset(made);
    }
    // One thread: CHOLMOD's factorization natively, the project's in wasm (SIMD kernels there).
    SupernodalReport report;
    if (!factor || !factorSupernodal(A, *factor, 1, c, report, &lower) || c.status != CHOLMOD_OK) return;
    ok = factor->minor >= n;  // else not positive definite
  }
};

SpdFactor::SpdFactor(const SparseMatrix& upper, std::vector<int> ordering)
    : SpdFactor(upper, std::move(ordering), KeptSymbolic()) {}

SpdFactor::SpdFactor(const SparseMatrix& upper, std::vector<int> ordering, KeptSymbolic symbolic)
    : impl_(std::make_unique<Impl>()) {
  impl_->ordering = std::move(ordering);
  impl_->symbolic = std::move(symbolic);
  cholmod_common& c = *impl_->common.get();
  c.nmethods =
      1;  // AMD alone where no ordering is given: METIS pays off only far beyond an atlas chart's size
  c.method[0].ordering = CHOLMOD_AMD;
  c.postorder = 1;
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.print = 0;
  c.error_handler = nullptr;
  impl_->factorize(upper);
}

bool SpdFactor::refactor(const SparseMatrix& upper) {
  impl_->factorize(upper);
  return impl_->ok;
}

KeptSymbolic SpdFactor::symbolic() const {
  return impl_->factor ? keptSymbolicOf(*impl_->factor) : KeptSymbolic();
}

std::vector<int> SpdFactor::permutation() const {
  const cholmod_factor* L = impl_->factor.get();
  if (!L || !L->is_super) return {};
  const int* perm = static_cast<const int*>(L->Perm);
  return std::vector<int>(perm, perm + L->n);
}

bool SpdFactor::analysisReused() const {
  return impl_->reused;
}

SpdFactor::~SpdFactor() = default;

bool SpdFactor::ok() const {
  return impl_->ok;
}

bool SpdFactor::solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) {
  Impl& s = *impl_;
  if (!s.ok || static_cast<size_t>(b.rows()) != s.n) return false;
  x.resize(b.rows(), b.cols());
  if (s.n == 0 || b.cols() == 0) return true;
  // A block in wasm: by supernodes on the lane kernels (CHOLMOD's would call Eigen's BLAS, one double at a
  // time there); one column keeps CHOLMOD's, the kernels' one-row products being scalar.
  if (blas::kLaneKernels && b.cols() > 1 && s.factor->is_super) {
    solveSupernodal(*s.factor, b.data(), static_cast<int>(b.cols()), x.data());
    return x.allFinite();
  }
  cholmod_dense rhs{};
  rhs.nrow = s.n;
  rhs.ncol = static_cast<size_t>(b.cols());
  rhs.nzmax = rhs.nrow * rhs.ncol;
  rhs.d = s.n;
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  CholmodDensePtr solution(cholmod_solve(CHOLMOD_A, s.factor.get(), &rhs, s.common.get()), {s.common.get()});
  if (!solution) return false;
  std::memcpy(x.data(), solution->x, rhs.nzmax * sizeof(double));
  return x.allFinite();
}

bool SpdFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Eigen::MatrixXd out;
  if (!solve(Eigen::MatrixXd(b), out)) return false;
  x = out.col(0);
  return true;
}

namespace {

// A fill-reducing permutation of A's graph by one of CHOLMOD's orderings, order(A, perm, common) -> ok; empty
// where it failed.
template <class Order>
std::vector<int> orderingBy(const SparseMatrix& upper, Order order) {
  const size_t n = static_cast<size_t>(upper.rows());
  if (n == 0 || upper.cols() != upper.rows() || !upper.isCompressed()) return {};
  CholmodCommon common;
  cholmod_common& c = *common.get();
  c.print = 0;
  c.error_handler = nullptr;
  cholmod_sparse A = upperTriangleView(upper);
  std::vector<int> perm(n);
  if (!order(A, perm.data(), c) || c.status != CHOLMOD_OK) return {};
  return perm;
}

}  // namespace

std::vector<int> nestedDissection(const SparseMatrix& upper) {
  return orderingBy(upper, [](cholmod_sparse& A, int* perm, cholmod_common& c) {
    return cholmod_metis(&A, nullptr, 0, 1, perm, &c);
  });
}

std::vector<int> minimumDegree(const SparseMatrix& upper) {
  return orderingBy(upper, [](cholmod_sparse& A, int* perm, cholmod_common& c) {
    return cholmod_amd(&A, nullptr, 0, perm, &c);
  });
}

bool solveSpdOnce(const SparseMatrix& upper, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  SpdFactor factor(upper);
  return factor.solve(b, x);
}

}  // namespace tvf
