#pragma once
// The symbolic analysis of A for a given fill-reducing ordering, as cholmod_analyze_p makes it (CHOLMOD's
// elimination tree, column counts, weighted postorder folded into the ordering, and supernodes, with the
// common object's settings), with P A P' permuted on the project's threads (solver/permuted_triangle.h)
// where cholmod_analyze_p transposes A four times on one (about 0.38 of the 1.25M-edge analysis's 0.64 s
// with a kept ordering, profiled under node).
// The lower triangle it permutes is the one the numeric factorization assembles from, so it is handed on.
#include <cholmod.h>

#include <vector>

#include "solver/permuted_triangle.h"

namespace tvf {

// A: symmetric, upper triangle stored, with values; perm: a permutation of its columns (as UserPerm of
// cholmod_analyze_p). Returns the symbolic factor (the caller frees it), with lower the lower triangle of
// P A P' with values for L's final permutation P (empty when the factor is simplicial), or nullptr where
// CHOLMOD failed (c.status says why) or perm is not a permutation.
cholmod_factor* analyzeOrdering(const cholmod_sparse& A, std::vector<int> perm, int parts, cholmod_common& c,
                                PermutedTriangle& lower);

}  // namespace tvf
