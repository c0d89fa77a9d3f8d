#pragma once
// c = d a + delta b + h (Eq. 3) by two Poisson solves. The inner product is *1 when it is positive on every
// edge and the (always positive) Whitney 1-form mass otherwise; the three parts are orthogonal in it.
#include <Eigen/Core>
#include <string>

#include "dec/hodge_star.h"
#include "dec/one_form_laplacian.h"

namespace tvf {

struct HodgeDecomposition {
  Eigen::VectorXd exact;     // d a: curl-free (d1 exact = 0)
  Eigen::VectorXd coexact;   // delta b: divergence-free (d0' P coexact = 0)
  Eigen::VectorXd harmonic;  // the rest: both (dimension 2g on a closed genus-g surface)
  // a per vertex (exact = d0 a) and b' per face (coexact = P^-1 d1' b'), each with zero mean over every
  // connected component (they are defined up to such constants).
  Eigen::VectorXd potential0, potential2;
  Eigen::VectorXd metric;  // the 1-form inner product used (diagonal)
  std::string metricName;
  double milliseconds = 0;  // the whole decomposition: assembly, two factorizations, solves
};

HodgeDecomposition hodgeDecompose(const SparseMatrix& d0, const SparseMatrix& d1,
                                  const MeshGeometry& geometry, const Eigen::VectorXd& oneForm);

// |part|^2 / |c|^2 in the decomposition's metric, c = exact + coexact + harmonic; they sum to 1 (the parts
// are orthogonal). All 0 for a zero field.
struct HodgeEnergyShares {
  double exact = 0, coexact = 0, harmonic = 0;
};
HodgeEnergyShares hodgeEnergyShares(const HodgeDecomposition& h);

}  // namespace tvf
