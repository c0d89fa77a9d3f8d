// SPDX-License-Identifier: GPL-2.0-or-later
#include "solver/spd_solve.h"

#include <cstring>

#include "solver/cholmod_handles.h"

namespace tvf {

struct SpdFactor::Impl {
  CholmodCommon common;
  CholmodFactorPtr factor{nullptr, {common.get()}};
  size_t n = 0;
  bool ok = false;
};

SpdFactor::SpdFactor(const SparseMatrix& upper) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  if (upper.cols() != upper.rows() || !upper.isCompressed()) return;
  s.n = static_cast<size_t>(upper.rows());
  if (s.n == 0) {
    s.ok = true;
    return;
  }
  cholmod_common& c = *s.common.get();
  c.nmethods = 1;  // AMD alone: METIS's nested dissection pays off only far beyond these systems' sizes
  c.method[0].ordering = CHOLMOD_AMD;
  c.postorder = 1;
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.print = 0;
  c.error_handler = nullptr;

  cholmod_sparse A = upperTriangleView(upper);

  s.factor.reset(cholmod_analyze(&A, &c));
  if (!s.factor || !cholmod_factorize(&A, s.factor.get(), &c) || c.status != CHOLMOD_OK) return;
  s.ok = s.factor->minor >= s.n;  // else not positive definite
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

bool solveSpdOnce(const SparseMatrix& upper, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  SpdFactor factor(upper);
  return factor.solve(b, x);
}

}  // namespace tvf
