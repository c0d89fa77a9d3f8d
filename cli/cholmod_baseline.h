#pragma once
// What plain CHOLMOD does with a design's system, for the benchmark to set the core's solver beside: a
// simplicial LDL' factor with AMD ordering, its full solve and its single-column update.
#include <nlohmann/json.hpp>

#include "common/sparse_matrix.h"

namespace tvf {

// The median over `repeat` (at least 5) of cholmod_solve of A x = b (plainAmdSolveMs) and of a rank-1 update
// of one diagonal entry (plainAmdUpdateMs), with the factor's nonzeros (plainAmdFactorNonzeros). A: symmetric
// positive definite (a kernel shifted by the caller).
nlohmann::json cholmodBaseline(const SparseMatrix& A, int repeat);

}  // namespace tvf
