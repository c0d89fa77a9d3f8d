#pragma once
// One solve of a sparse SPD system, factored for it alone and then dropped: CHOLMOD's supernodal Cholesky
// with AMD ordering. For small systems made once each (an atlas chart's conformal map), where
// FactoredSystem's machinery for updates (the conversion to LDL', the kept forward solution) would be
// overhead: a chart of 50k vertices factors ~4x faster this way than by Eigen's simplicial LDL'.
#include <Eigen/Core>

#include "common/sparse_matrix.h"

namespace tvf {

// Solves A x = b with `upper` the upper triangle (diagonal included) of A. Returns false, leaving x
// unspecified, when A is not numerically positive definite or the solution is not finite.
bool solveSpdOnce(const SparseMatrix& upper, const Eigen::VectorXd& b, Eigen::VectorXd& x);

}  // namespace tvf
