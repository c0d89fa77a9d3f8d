#pragma once
// Sparse SPD systems factored for their own solves and then dropped: CHOLMOD's supernodal Cholesky with AMD
// ordering or a given one (in wasm its numeric factorization is the project's,
// solver/supernodal_cholesky.h, on SIMD kernels). For systems made once each (an atlas chart's conformal map)
// or again after every edit with their analysis kept (a stripe pattern's energy for LOBPCG), where
// FactoredSystem's machinery for updates (the conversion to LDL', the kept forward solution) would be
// overhead. armadillo-sub2's 648 chart solves took 2.3 s this way, natively; Eigen's simplicial LDL' of A^T A
// (its ordering, analysis, factorization and the product) had about 48 % of a 10 s run's profile.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "common/sparse_matrix.h"
#include "solver/kept_symbolic.h"

namespace tvf {

class SpdFactor {
 public:
  // Factors A, with `upper` its upper triangle (diagonal included, compressed; read, not kept). ok() says
  // whether A was numerically positive definite. ordering: a fill-reducing permutation of A's rows (as
  // CHOLMOD's UserPerm) to analyse with, such as nestedDissection's; empty: AMD. One thread
  // (a stripe pattern's energy on two, in the page beside its renderer, took no less: 0.80 against 0.77 s on
  // armadillo-sub2).
  explicit SpdFactor(const SparseMatrix& upper, std::vector<int> ordering = {});
  // The same with a symbolic factor made before for `ordering` (symbolic(), or its expandedSymbolic with the
  // ordering expanded as well), checked against A (symbolicFromKept): no analysis where it fits, an analysis
  // where it does not.
  SpdFactor(const SparseMatrix& upper, std::vector<int> ordering, KeptSymbolic symbolic);
  ~SpdFactor();
  SpdFactor(const SpdFactor&) = delete;
  SpdFactor& operator=(const SpdFactor&) = delete;

  bool ok() const;
  // Factors A again, reusing the symbolic analysis (ordering, supernodes) when A has the pattern of the
  // matrix it was made for, else analysing it afresh. Returns ok().
  bool refactor(const SparseMatrix& upper);
  bool analysisReused() const;  // the last factorization reused the analysis
  // Solves A x = b; false (x unspecified) when the factor is not ok or the solution is not finite.
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // The same for every column of b at once.
  bool solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x);
  // The symbolic factor and the permutation it was made for (the ordering with its postorder folded in);
  // empty where the factor is not supernodal.
  KeptSymbolic symbolic() const;
  std::vector<int> permutation() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// METIS's nested dissection of the graph of A (symmetric, `upper` its upper triangle), postordered: a
// permutation as SpdFactor takes it. Empty where METIS failed.
std::vector<int> nestedDissection(const SparseMatrix& upper);

// AMD's approximate minimum degree ordering of the same graph, as SpdFactor takes it (which then postorders
// it). Empty where AMD failed.
std::vector<int> minimumDegree(const SparseMatrix& upper);

// Solves A x = b once. Returns false, leaving x unspecified, when A is not numerically positive definite or
// the solution is not finite.
bool solveSpdOnce(const SparseMatrix& upper, const Eigen::VectorXd& b, Eigen::VectorXd& x);

}  // namespace tvf
