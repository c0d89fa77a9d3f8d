#pragma once
// A rank-k diagonal update A + E W E' of a factored A = L D L' (L unit lower triangular, simplicial), held
// beside the factor instead of in it, so that the solve after a stroke does not wait for the factor's update:
// by the Woodbury identity, with G = L^-1 E W^1/2 and K = I + G' D^-1 G (k x k, definite, eigenvalues >= 1),
//
//   (A + E W E')^-1 b = L^-T D^-1 (u - G K^-1 G' D^-1 u),   u = L^-1 b.
//
// G is nonzero only on Q, the union of the elimination-tree paths from the k update positions to the root,
// where it costs one forward substitution with k right-hand sides: one multiply-add per entry of L on Q and
// per right-hand side whose path passes there, against two per entry and per column for the update itself
// (Method C1), and the right-hand sides are independent, so they split across threads without a barrier.
// The update is then applied to the factor after the solve's result has gone (FactoredSystem::deferUpdate).
#include <cholmod.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "solver/factor_columns.h"

namespace tvf {

class WoodburyCorrection {
 public:
  // G and the Cholesky factor of K for the update columns sqrt(weights[m]) e_{positions[m]} (positions in L's
  // order, ascending). storage: zero on entry, `capacity` doubles; slot: L.n ints of scratch. Returns false,
  // keeping nothing and leaving storage zero, when G does not fit in storage, or when the weights are so
  // heavy against A that the correction would lose precision the update keeps (K's diagonal past 1e6).
  bool prepare(const cholmod_factor& L, const int* positions, const double* weights, int k, double* storage,
               size_t capacity, int* slot, int parts);
  // y <- y - G K^-1 G' D^-1 y, which changes y on Q only (y: L^-1 b, n values in L's order).
  void correct(const cholmod_factor& L, double* y) const;
  // Zeroes the storage G used and forgets the update.
  void clear();
  bool empty() const { return k_ == 0; }

 private:
  bool collectPaths(const FactorColumns& L, int n, const int* positions, int k, size_t capacity, int* slot);
  void spreadRanges(const FactorColumns& L, const int* positions, const double* weights, const int* slot);
  bool substituteForward(const FactorColumns& L, const int* slot, int parts);
  Eigen::MatrixXd identityPlusGram(const FactorColumns& L, int parts) const;

  int k_ = 0;
  int stride_ = 0;  // doubles per row of G: k rounded up to whole cache lines, so parts never share one
  double* g_ = nullptr;
  std::vector<int> path_;                 // Q, ascending (children before parents)
  std::vector<int> low_, high_;           // per row of Q: the range of right-hand sides nonzero there
  Eigen::LLT<Eigen::MatrixXd> cholesky_;  // of K
};

}  // namespace tvf
