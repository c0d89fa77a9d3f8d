// SPDX-License-Identifier: GPL-2.0-or-later
#include "solver/spd_solve.h"

#include <cstring>

#include "solver/cholmod_handles.h"

namespace tvf {

bool solveSpdOnce(const SparseMatrix& upper, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const auto n = static_cast<size_t>(upper.rows());
  if (upper.cols() != upper.rows() || static_cast<size_t>(b.size()) != n || !upper.isCompressed())
    return false;
  if (n == 0) {
    x.resize(0);
    return true;
  }
  CholmodCommon common;
  common->nmethods = 1;  // AMD alone: METIS's nested dissection pays off only far beyond a chart's size
  common->method[0].ordering = CHOLMOD_AMD;
  common->postorder = 1;
  common->supernodal = CHOLMOD_SUPERNODAL;
  common->print = 0;
  common->error_handler = nullptr;

  cholmod_sparse A{};  // a view of `upper`, not a copy
  A.nrow = A.ncol = n;
  A.nzmax = static_cast<size_t>(upper.nonZeros());
  A.p = const_cast<int*>(upper.outerIndexPtr());
  A.i = const_cast<int*>(upper.innerIndexPtr());
  A.x = const_cast<double*>(upper.valuePtr());
  A.stype = 1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;

  CholmodFactorPtr L(cholmod_analyze(&A, common.get()), {common.get()});
  if (!L || !cholmod_factorize(&A, L.get(), common.get()) || common->status != CHOLMOD_OK) return false;
  if (L->minor < n) return false;  // not positive definite

  cholmod_dense rhs{};
  rhs.nrow = n;
  rhs.ncol = 1;
  rhs.nzmax = n;
  rhs.d = n;
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  CholmodDensePtr solution(cholmod_solve(CHOLMOD_A, L.get(), &rhs, common.get()), {common.get()});
  if (!solution) return false;
  x.resize(static_cast<Eigen::Index>(n));
  std::memcpy(x.data(), solution->x, n * sizeof(double));
  return x.allFinite();
}

}  // namespace tvf
