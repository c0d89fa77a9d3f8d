#pragma once
// The numeric supernodal Cholesky factorization L L' = P A P', with the independent subtrees of the
// supernodal elimination tree factored on separate threads.
//
// It fills the same supernodal factor CHOLMOD's cholmod_factorize would (the symbolic analysis is CHOLMOD's,
// and each supernode is computed as cholmod_super_numeric computes it: left-looking, the descendants'
// updates by dsyrk/dgemm, then dpotrf and dtrsm), so the conversion to the simplicial LDL' that the updates,
// downdates and solves use follows unchanged. A descendant updates only its ancestors, so subtrees that are
// not nested never read each other's columns; a nested dissection makes them even. The top of the tree (the
// separators above the cut, solver/subtree_partition.h) follows the subtrees, and its largest supernodes
// split their dense work across the threads. Every supernode's sums are the same operations in the same
// order whatever the number of threads (a large one's work is cut into fixed bands, which the threads share
// out; the descendants' updates are summed in index order): the factor on N threads is the one-thread factor
// bit for bit. Against CHOLMOD's own cholmod_factorize only the order of the sums differs: round-off.
#include <cholmod.h>

#include <string>

#include "solver/permuted_triangle.h"

namespace tvf {

struct SupernodalReport {
  int parts = 1;             // threads the factorization ran on
  int groups = 1;            // groups of subtrees they factored side by side, before the top on all of them
  double subtreeShare = 0;   // of the estimated work, the share in the subtrees factored side by side
  int bandedSupernodes = 0;  // supernodes whose work went in bands (dense work above 4e6 multiply-adds)
  std::string singleThreadWhy;  // when more threads were asked for and one ran: why
};

// For a test: the next factorization's helper tasks fail as a thread that cannot start would, once.
void failNextSupernodalThreads();

// For a test: whether one thread runs the project's factorization (the default) rather than CHOLMOD's;
// returns the previous choice.
bool setOwnFactorizationAlone(bool own);

// A: symmetric, upper triangle stored (as for cholmod_factorize); L: CHOLMOD's symbolic supernodal analysis
// of A (or a numeric supernodal factor of the same analysis, overwritten). Runs on up to `parts` threads
// (common/thread_team.h); on one, or where the tree has no subtrees worth splitting, the same supernode by
// supernode factorization on this thread (in wasm its dense kernels, solver/lane_kernels.h, are SIMD where
// the BLAS is not). A simplicial L is CHOLMOD's cholmod_factorize's, on one thread. Sets c.status and L.minor
// as cholmod_factorize does (CHOLMOD_NOT_POSDEF, with L.minor the first column that failed, when A is not
// numerically positive definite; the factor is then not usable). Returns false only when CHOLMOD could not
// allocate. lower: the lower triangle of P A P' with values where the analysis made it (symbolic_analysis.h),
// taken instead of permuting A again; nullptr or empty: permuted here.
bool factorSupernodal(cholmod_sparse& A, cholmod_factor& L, int parts, cholmod_common& c,
                      SupernodalReport& report, PermutedTriangle* lower = nullptr);

}  // namespace tvf
