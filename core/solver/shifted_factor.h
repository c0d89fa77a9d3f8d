#pragma once
// The factor of the design's system A = base + sum_k w_k e_{r_k} e_{r_k}' (constraint rows with one nonzero
// each); `base` is always passed as its upper triangle, compressed, every diagonal entry stored
// (common/sparse_matrix.h: upperTriangle). The base matrix M is only semidefinite (its kernel: harmonic
// fields, and more with free boundaries), so what is factored is A + sigma * mean diagonal on the edges of
// components with a kernel, with sigma as small as CHOLMOD accepts (Sec. 5.1). Solves are refined against the
// unshifted A. Constraint changes are rank updates of the factor; downdates are rationed by how much
// precision they cost, and a solve after updates is checked and refactors once if the updated factor lost
// precision.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "common/sparse_matrix.h"
#include "solver/factored_system.h"

namespace tvf {

// sum_k weights[k] e_{rows[k]} e_{rows[k]}', in a fixed order (the order the constraints were added).
struct DiagonalTerms {
  std::vector<int32_t> rows;
  std::vector<double> weights;
};

// base + the terms (entries on one row summed).
SparseMatrix plusDiagonal(const SparseMatrix& base, const DiagonalTerms& terms);

// What the last factorization did, for the session's stats.
struct FactorReport {
  double analyzeMs = 0, factorMs = 0;
  double convertMs = 0;  // of factorMs, the factor turned into LDL' for the updates (solver/ldl_conversion.h)
  double dissectionMs = 0;  // of analyzeMs, FactorTimings::dissectionMs
  bool analysisReused = false;
  bool symbolicReused = false;  // FactorTimings::symbolicReused
  int64_t factorNonzeros = 0;
  double kernelShift = 0;      // sigma, relative to the mean diagonal
  std::string kernelHandling;  // how the kernel was made definite, in words
  std::string factorKind;      // e.g. "supernodal LL' (AMD)"
  int64_t factorizations = 0;  // numeric factorizations since the factor was made (edits must add none)
  int factorThreads = 1;       // FactorTimings::factorThreads
  int factorGroups = 1;        // FactorTimings::factorGroups
  std::string singleThreadWhy;
};

class ShiftedFactor {
 public:
  // kernelEdges[e] != 0: edge e lies in a component whose base matrix has a kernel (handles or boundary
  // loops); those edges get the shift, the others only if the factorization fails without it.
  explicit ShiftedFactor(std::vector<uint8_t> kernelEdges, FillOrdering ordering = FillOrdering::Metis);

  void setOrdering(FillOrdering ordering);  // forgets the factor and the ordering
  // The mesh's edges (2 vertices each): the METIS ordering dissects its vertex graph (FactoredSystem).
  void setEdgeGraph(std::vector<int32_t> edgeVertices, int32_t numVertices);
  void setThreads(int threads);           // FactoredSystem::setThreads
  KeptOrdering keptOrdering() const;      // FactoredSystem::keptOrdering
  bool adoptOrdering(KeptOrdering kept);  // FactoredSystem::adoptOrdering
  void setKeepSymbolic(bool keep);        // FactoredSystem::setKeepSymbolic
  bool keptOrderingIsNew() const;         // FactoredSystem::keptOrderingIsNew
  int threads() const;
  void setMemoryLimit(double bytes);  // 0: the machine's physical memory
  double memoryLimit() const;

  // Whether the factor stands for the current system: false before the first factorization, after
  // invalidate() and after a refused downdate.
  bool current() const;
  void invalidate();  // the base matrix changed
  // Frees the factor, keeping its ordering (FactoredSystem::release); not current until factored again.
  void release();

  // Factors base + terms + the shift, raising the shift (and spreading it to every edge) until CHOLMOD finds
  // the matrix definite. Throws InputError when even the largest shift fails, or when the factor would need
  // more memory than the limit.
  void factor(const SparseMatrix& base, double scale, const DiagonalTerms& terms);
  // Adds (or with downdate, removes) `change` by one rank update; nothing while the factor is not current.
  // A downdate that would take the weight removed since the factorization past the budget is not done: the
  // factor is then no longer current, and the next solve refactors.
  void update(const DiagonalTerms& change, double scale, bool downdate);
  // Whether update() holds an addition beside the factor (FactoredSystem::deferUpdate), for
  // applyDeferred() to put into it after the solve that needed it; downdates are always done at once.
  void setDeferredUpdates(bool defer);
  void applyDeferred();
  // Solves (base + terms) x = b: with the factor, plus one step of iterative refinement against the
  // unshifted matrix. After updates, a solution that is not finite, or after downdates one whose backward
  // error is beyond round-off, makes it refactor and solve again, once. base, scale and terms must be those
  // the factor holds.
  void solve(const SparseMatrix& base, double scale, const DiagonalTerms& terms, const Eigen::VectorXd& b,
             Eigen::VectorXd& x);

  const FactorReport& report() const;
  double lastUpdateMs() const;          // the last rank update that was done (or held beside the factor)
  double lastDeferredUpdateMs() const;  // the last deferred update put into the factor
  int32_t precisionRefactors() const;   // how many times solve() found an updated factor wanting
  int64_t incrementalSolves() const;    // FactoredSystem::incrementalSolves
  int64_t supernodalSolves() const;     // FactoredSystem::supernodalSolves

 private:
  // The shift and the terms, summed per row.
  std::vector<double> shiftedDiagonal(double scale, const DiagonalTerms& terms) const;
  Eigen::VectorXd factoredProduct(const SparseMatrix& base, double scale, const DiagonalTerms& terms,
                                  const Eigen::VectorXd& x) const;
  double factoredNorm(double scale, const DiagonalTerms& terms);
  bool solvesToRoundOff(const SparseMatrix& base, double scale, const DiagonalTerms& terms,
                        const Eigen::VectorXd& b, const Eigen::VectorXd& x);
  void refineAgainstUnshiftedSystem(const SparseMatrix& base, const DiagonalTerms& terms,
                                    const Eigen::VectorXd& b, Eigen::VectorXd& x);

  std::vector<uint8_t> kernelEdges_;
  bool anyKernel_ = false;
  FactoredSystem system_;
  bool stale_ = true;
  double memoryLimit_ = 0;
  double shift_ = 0;
  bool shiftEverywhere_ = false;
  double downdateLoad_ = 0;           // relative weight removed by downdates since the last factorization
  bool updatedSinceFactor_ = false;   // the factor is no longer the one CHOLMOD computed from scratch
  bool downdatedSinceCheck_ = false;  // downdated since the last solve that checked the factor
  double baseNorm_ = 0;               // infinity norm of the base matrix last factored
  Eigen::VectorXd termSums_;          // scratch: the terms summed per row
  int32_t precisionRefactors_ = 0;
  double updateMs_ = 0, deferredUpdateMs_ = 0;
  bool deferUpdates_ = false;
  FactorReport report_;
};

}  // namespace tvf
