#pragma once
// The forward substitution y = L^-1 P b of the last right-hand side, kept current across rank updates of
// the simplicial LDL' factor (L unit lower triangular), so that a solve after a stroke only redoes the
// columns the stroke touched and then the backward substitution.
//
// An update (or a change of b on a few rows) changes L and y only on the columns of the elimination-tree
// paths from those rows to the root. That set Q is closed under ancestors (a column's rows are its
// ancestors), so a row outside Q has entries only in columns outside Q, and y outside Q stays exact. On Q
// the substitution is redone from r = P b less the contributions of the columns outside Q, which the old L
// gives as r(Q) = y(Q) + (L_old - I)(Q, Q) y(Q), accumulated before an update changes those columns; the
// new L then solves on Q alone. This is cholmod_updown_solve's algorithm, with all of an edit's updates and
// its change of b taken in one pass over Q instead of two per group of eight update columns.
#include <cholmod.h>

#include <cstdint>
#include <vector>

namespace tvf {

class ForwardSolution {
 public:
  // Forgets y (and frees its storage): the next solve substitutes in full.
  void invalidate();

  // Before L's columns on the paths from `columns` (positions in L) to the root are changed: keeps what
  // y needs from the old L. Nothing while y is not valid.
  void beforeUpdate(const cholmod_factor& L, const int* columns, int count);

  // Brings y to L^-1 bPermuted on the columns that need it, when y is valid, bPermuted differs from the
  // last one on at most a few rows, has not shrunk far below the right-hand sides y solved since its last
  // full substitution, and few incremental substitutions were done since then (each redoes Q from rounded
  // values). Returns false, doing nothing, otherwise: then the caller
  // substitutes in full and hands the result to setFull.
  bool substituteIncrementally(const cholmod_factor& L, const double* bPermuted);
  void setFull(const double* bPermuted, const double* y, int n);

  const std::vector<double>& y() const { return y_; }
  int64_t incrementalCount() const { return incrementalTotal_; }

 private:
  void addPaths(const cholmod_factor& L, const int* columns, int count);
  void substituteOnPending(const cholmod_factor& L);
  void clearPending();

  bool valid_ = false;
  int incremental_ = 0;  // incremental substitutions since the last full one
  int64_t incrementalTotal_ = 0;
  // The largest |b| (infinity norm) y has solved since its last full substitution.
  double largestSinceFull_ = 0;
  std::vector<double> y_;       // L y = bLast_
  std::vector<double> bLast_;   // the permuted right-hand side y solves
  std::vector<double> r_;       // on pending_: P b less the contributions of L's columns outside pending_
  std::vector<uint8_t> inSet_;  // membership of pending_
  std::vector<int> pending_;    // Q: columns whose y is to be redone (closed under ancestors)
  std::vector<int> changed_;    // rows where b changed (scratch)
};

}  // namespace tvf
