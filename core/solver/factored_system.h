#pragma once
// A sparse SPD matrix factored once by CHOLMOD and then modified only by rank-1 updates/downdates of its
// factor (cholmod_updown), as constraint rows with a single nonzero come and go. An addition may be held
// beside the factor for the solves after it (deferUpdate) and put into it later.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/sparse_matrix.h"
#include "solver/kept_symbolic.h"

namespace tvf {

enum class FillOrdering { Amd, Metis };

// How solve() substitutes backward: CHOLMOD's column-by-column L^-T (each entry a row index and a gather), or
// supernode by supernode, gathering each supernode's rows once, on one thread or several
// (solver/backward_substitution.h), the same sums in the same order on any number of threads. On bunny00 the
// supernodes take wasm's solve after an edit from 12.7-12.9 to 10.4-10.5 ms; natively, on one thread, they
// are ~10 % slower than CHOLMOD's columns (docs/method.md), but the columns' sums differ from the
// supernodes', and the field would then change with the number of threads: every build takes the supernodes.
enum class BackwardKernel { Columns, Supernodes };

constexpr BackwardKernel kDefaultBackwardKernel = BackwardKernel::Supernodes;

struct FactorTimings {
  double analyzeMs = 0, factorMs = 0, convertMs = 0;
  // Of analyzeMs, the nested dissection of the mesh's vertex graph (solver/edge_dissection.h; 0 when none
  // was made).
  double dissectionMs = 0;
  // The last factor() reused the previous symbolic analysis (same sparsity pattern): no ordering was
  // computed.
  bool analysisReused = false;
  // ... and took its symbolic factor from a kept one (KeptOrdering::symbolic): no analysis at all.
  bool symbolicReused = false;
  // Threads the last numeric factorization ran on (solver/supernodal_cholesky.h), and, when more were
  // asked for and it ran on one, why.
  int factorThreads = 1;
  int factorGroups = 1;  // the groups of subtrees factored side by side (at most factorThreads)
  std::string singleThreadWhy;
  double subtreeShare = 0;   // of its estimated work, the share factored side by side
  int bandedSupernodes = 0;  // supernodes whose work was cut into bands (solver/supernodal_cholesky.h)
};

// A fill-reducing ordering kept beyond the system that computed it (the page's IndexedDB, the CLI's
// --ordering-cache): the permutation, a hash of the sparsity pattern it was computed for, and how. Ordering
// depends on the mesh alone, and is most of the analysis: 2.3 of armadillo-sub2's 4.5 s before its first
// field.
struct KeptOrdering {
  std::vector<int32_t> perm;  // empty: none
  uint64_t pattern = 0;
  FillOrdering ordering = FillOrdering::Metis;
  bool dissection = false;  // METIS: the mesh's nested dissection (edge_dissection.h), not CHOLMOD's own
  // The supernodal symbolic factor of perm on the pattern (solver/kept_symbolic.h), where one was kept: with
  // it a factorization of the same pattern analyzes nothing. Empty: none (a simplicial factor, or not asked
  // for: setKeepSymbolic).
  KeptSymbolic symbolic;
};

class FactoredSystem {
 public:
  explicit FactoredSystem(FillOrdering ordering = FillOrdering::Metis);
  ~FactoredSystem();
  FactoredSystem(FactoredSystem&&) noexcept;
  FactoredSystem& operator=(FactoredSystem&&) noexcept;

  // Analyzes and factors A (symmetric; only its upper triangle is read). Returns false if A is not
  // numerically positive definite. The fill-reducing ordering and symbolic analysis are computed once and
  // reused while A keeps the sparsity pattern of the matrix they were computed for.
  // Throws InputError, before the numeric factorization, when the symbolic
  // analysis says the factor would need more than the memory limit.
  bool factor(const SparseMatrix& A);
  // The same for upper + diag(diagonal) (diagonal empty: none), with `upper` the matrix's upper triangle,
  // compressed: it is read in place, and only its values are copied, to add the diagonal, until the
  // numeric factorization is done (the conversion for updates that follows is the memory peak).
  bool factorUpper(const SparseMatrix& upper, const std::vector<double>& diagonal);
  // Forgets the factor and the symbolic analysis; the next factor() orders with `ordering`.
  void setOrdering(FillOrdering ordering);
  // The ordering of the last analysis (or the one adopted since), to keep beyond this system.
  KeptOrdering keptOrdering() const;
  // An ordering kept from an earlier system: the next factor() of a matrix with its pattern uses it instead
  // of ordering again (one of another pattern is ignored then, as stale or foreign), and its symbolic factor,
  // if it has one that fits the matrix, instead of the analysis. Returns false, and adopts nothing, for one
  // made with the other FillOrdering or that is not a permutation of 0 .. n-1.
  bool adoptOrdering(KeptOrdering kept);
  // Whether keptOrdering() carries the symbolic factor of the last analysis (a copy of its supernodes' rows:
  // 35 MB at 1.25M edges, so only while asked for). Off by default; turning it off lets the copy go.
  void setKeepSymbolic(bool keep);
  // Whether keptOrdering() holds what its factorization did not take from an adopted one, so that a cache of
  // them has something to store: an ordering computed, or a symbolic factor analyzed (and kept) for an
  // adopted ordering that came without one or with one that did not fit.
  bool keptOrderingIsNew() const;
  // The mesh behind a 1-form system (2 vertices per edge, one edge per row of A): with it the METIS ordering
  // is a nested dissection of the vertex graph (solver/edge_dissection.h) instead of CHOLMOD's of A's graph.
  void setEdgeGraph(std::vector<int32_t> edgeVertices, int32_t numVertices);
  void setMemoryLimit(double bytes);  // 0: no limit
  // Threads for the numeric factorization's subtrees and the backward substitution (default: the cores
  // there are; at most what common/thread_team.h provides, to which larger numbers are cut). The factor and
  // the solves are the same bit for bit whatever the number (the default backward kernel's).
  void setThreads(int threads);
  int threads() const;
  // Threads for the numeric factorization alone (setThreads sets it too): a test compares the backward
  // substitution on several threads over one factor.
  void setFactorThreads(int threads);
  void setBackwardKernel(BackwardKernel kernel);
  double estimatedBytes() const;  // the last analysis' estimate of the factor's peak memory
  // L L' +/- sum_k w_k e_{row_k} e_{row_k}' in one cholmod_updown call; weights must be positive.
  // Applies any deferred update first.
  void updateDiagonal(const std::vector<int32_t>& rows, const std::vector<double>& weights, bool downdate);
  // The same update (positive weights) held beside the factor: solves apply it by the Woodbury identity
  // (solver/woodbury_correction.h) until applyDeferred() puts it into the factor, which every other change of
  // the factor does first and factor() makes moot. Applies it at once, returning false, when its columns'
  // paths to the root are too many for the update's workspace.
  bool deferUpdate(const std::vector<int32_t>& rows, const std::vector<double>& weights);
  void applyDeferred();
  bool hasDeferred() const;
  // Solves A x = b. The forward substitution L^-1 P b is kept: after updates and a change of b on a few
  // rows (a stroke's), the next solve redoes it only on the elimination-tree paths they changed, then
  // substitutes backward (solver/forward_solution.h).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Solves A x = b without touching what solve() keeps (a right-hand side that is not the design's, such
  // as a refinement's residual).
  void solveOnce(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  int64_t incrementalSolves() const;  // solves whose forward substitution was incremental
  int64_t supernodalSolves() const;   // solves and solveOnce calls that substituted backward by supernodes

  bool factored() const;
  // Frees the numeric factor and what was made from it (solves' state, a held update, the updates'
  // workspace), keeping the ordering: the next factor() of the same pattern reuses it. For a system kept out
  // of use, which is factored again when it comes back anyway.
  void release();
  int64_t factorNonzeros() const;
  const FactorTimings& timings() const;
  std::string description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tvf
