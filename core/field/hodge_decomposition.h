#pragma once
// c = d a + delta b + h (Eq. 3) by two Poisson solves. The inner product is *1 when it is positive on every
// edge and the (always positive) Whitney 1-form mass otherwise; the three parts are orthogonal in it.
#include <Eigen/Core>
#include <string>

#include "dec/hodge_star.h"
#include "dec/one_form_laplacian.h"

namespace tvf {

struct HodgeDecomposition {
  Eigen::VectorXd exact;     // d a: curl-free
  Eigen::VectorXd coexact;   // delta b: divergence-free
  Eigen::VectorXd harmonic;  // the rest
  Eigen::VectorXd potential0, potential2;
  Eigen::VectorXd metric;  // the 1-form inner product used (diagonal)
  std::string metricName;
};

HodgeDecomposition hodgeDecompose(const SparseMatrix& d0, const SparseMatrix& d1,
                                  const MeshGeometry& geometry, const Eigen::VectorXd& oneForm);

}  // namespace tvf
