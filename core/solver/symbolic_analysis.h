#pragma once
// The symbolic analysis of A for a given fill-reducing ordering, as cholmod_analyze_p makes it (CHOLMOD's
// elimination tree, column counts, weighted postorder folded into the ordering, and supernodes, with the
// common object's settings), with P A P' permuted on the project's threads (solver/permuted_triangle.h)
// where cholmod_analyze_p transposes A four times on one (about 0.38 of the 1.25M-edge analysis's 0.64 s
// with a kept ordering, profiled under node).
// The lower triangle it permutes is the one the numeric factorization assembles from, so it is handed on.
// The same symbolic factor can come instead from one kept beyond the system that made it (kept_symbolic.h),
// checked against the matrix: then only that lower triangle is made.
#include <cholmod.h>

#include <vector>

#include "solver/kept_symbolic.h"
#include "solver/permuted_triangle.h"

namespace tvf {

// A: symmetric, upper triangle stored, with values; perm: a permutation of its columns (as UserPerm of
// cholmod_analyze_p). Returns the symbolic factor (the caller frees it), with lower the lower triangle of
// P A P' with values for L's final permutation P (empty when the factor is simplicial), or nullptr where
// CHOLMOD failed (c.status says why) or perm is not a permutation.
cholmod_factor* analyzeOrdering(const cholmod_sparse& A, std::vector<int> perm, int parts, cholmod_common& c,
                                PermutedTriangle& lower);

// L's symbolic part, to keep (a supernodal factor, symbolic or numeric); empty for a simplicial one.
KeptSymbolic keptSymbolicOf(const cholmod_factor& L);

// The same symbolic factor from a kept one, with `lower` as analyzeOrdering hands it on. The kept one is
// checked against A first: its arrays have the shapes and ranges of a supernodal factor of n columns, every
// entry of P A P' lies in its pattern, and each supernode's rows below its columns lie in its parent's (the
// pattern is closed under elimination), so that a numeric factorization on it stays in its arrays and gives L
// (the pattern may hold zeros L lacks). nullptr, and `lower` empty, where it does not fit A (stale or
// damaged) or CHOLMOD could not allocate: the caller analyzes instead.
cholmod_factor* symbolicFromKept(const cholmod_sparse& A, const std::vector<int>& perm,
                                 const KeptSymbolic& kept, int parts, cholmod_common& c,
                                 PermutedTriangle& lower);

}  // namespace tvf
