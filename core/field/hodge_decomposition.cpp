#include "field/hodge_decomposition.h"

#include <Eigen/SparseCholesky>
#include <stdexcept>

namespace tvf {
namespace {

// Both Poisson matrices are singular only by constants per component (and the right-hand sides are
// orthogonal to those), so a relative shift of 1e-12 selects the minimum-norm potential.
Eigen::VectorXd solveSemidefinite(SparseMatrix A, const Eigen::VectorXd& b) {
  const double shift = 1e-12 * meanDiagonal(A);
  for (int k = 0; k < A.rows(); ++k) A.coeffRef(k, k) += shift;
  Eigen::SimplicialLDLT<SparseMatrix> solver(A);
  if (solver.info() != Eigen::Success) throw std::runtime_error("Hodge decomposition: factorization failed");
  return solver.solve(b);
}

}  // namespace

HodgeDecomposition hodgeDecompose(const SparseMatrix& d0, const SparseMatrix& d1, const MeshGeometry& g,
                                  const Eigen::VectorXd& c) {
  HodgeDecomposition h;
  const bool starPositive = g.star1.size() > 0 && g.star1.minCoeff() > 0;
  h.metric = starPositive ? g.star1 : g.whitneyMass1;
  h.metricName = starPositive ? "star1" : "whitney-mass";
  const Eigen::VectorXd& P = h.metric;
  // Exact part: min |c - d a|_P  <=>  d0' P d0 a = d0' P c.
  const SparseMatrix L0 = d0.transpose() * P.asDiagonal() * d0;
  h.potential0 = solveSemidefinite(L0, d0.transpose() * P.asDiagonal() * c);
  h.exact = d0 * h.potential0;
  // Coexact part: delta b = P^-1 d1' b' with (d1 P^-1 d1') b' = d1 c (b' = *2 b).
  const Eigen::VectorXd Pinv = P.cwiseInverse();
  const SparseMatrix L2 = d1 * Pinv.asDiagonal() * d1.transpose();
  h.potential2 = solveSemidefinite(L2, d1 * c);
  h.coexact = Pinv.asDiagonal() * (d1.transpose() * h.potential2);
  h.harmonic = c - h.exact - h.coexact;
  return h;
}

}  // namespace tvf
