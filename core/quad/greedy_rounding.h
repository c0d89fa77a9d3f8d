#pragma once
// Mixed-integer least squares by greedy rounding (Bommes, Zimmer, Kobbelt 2009, Sec. 4.2): minimise
// z^T K z - 2 b^T z with some unknowns pinned and some integer, by fixing the integers one (or, when there
// are many, a tenth of those left) at a time, each time the one the relaxed solution puts nearest an
// integer, and solving again.
//
// The continuous unknowns (hundreds of thousands) are eliminated once: K_CC is factored a single time and
// the integers' Schur complement S = K_II - K_IC K_CC^-1 K_CI (dense, as small as the integers are few) is
// what each rounding step solves. The continuous solution follows from the integers in one more solve. K_CC
// gets a ridge of 1e-10 of its mean diagonal, so that a chart left free to slide (placed by integers in one
// direction only) still factors.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "common/sparse_matrix.h"

namespace tvf {

struct GreedyRounding {
  Eigen::VectorXd z;
  int32_t roundingSteps = 0;
  bool ok = false;  // false: K_CC was not positive definite (or the solve not finite)
};

// K: the full symmetric matrix; integer: 1 per integer unknown; pinned: (unknown, value). progress (may be
// empty) gets the fraction done (the Schur complement's columns, then the integers fixed); returning false
// stops (ok stays false).
GreedyRounding roundGreedily(const SparseMatrix& K, const Eigen::VectorXd& b,
                             const std::vector<uint8_t>& integer,
                             const std::vector<std::pair<int32_t, double>>& pinned,
                             const std::function<bool(double)>& progress = {});

}  // namespace tvf
