#pragma once
// The backward substitution x = L^-T D^-1 y of CHOLMOD's simplicial LDL' factor (L unit lower triangular, D
// on its diagonal), done supernode by supernode.
//
// Column by column (CHOLMOD's own, in groups of up to four columns with the same rows), each entry of L costs
// a row index and a gather of x through it. The columns of a fundamental supernode f..l share their rows R
// below the supernode (column c holds c..l, then R), so x(R) is gathered once per supernode into a contiguous
// buffer and each column's part on R is a dense dot product of contiguous values. The row indices on R are
// read once per supernode instead of once per group of columns, and the dot products run in two-double vector
// lanes, up to four columns per pass over the gathered rows. In wasm, which has no vector gathers, this is
// the faster backward substitution; natively CHOLMOD's, compiled for the machine, stays ahead on one thread
// (BackwardKernel in solver/factored_system.h).
//
// Subtrees of the supernodes' elimination tree that are not nested read none of each other's columns: below
// a top done first, they go to several threads (solver/subtree_partition.h, common/thread_team.h). Each
// column's sums are the same operations in the same order either way, so the result does not depend on the
// number of threads, bit for bit.
//
// Diagonal updates keep L's pattern (the path of a column with one entry lies in L's pattern), so the
// supernodes found after a factorization stay valid until the next one.
#include <cholmod.h>

#include <vector>

#include "solver/subtree_partition.h"

namespace tvf {

class BackwardSubstitution {
 public:
  // Forgets the supernodes: L's pattern is about to change (a factorization).
  void invalidate();

  // How many threads the substitution may use (1: the calling thread alone); the next solve splits the
  // supernodes again.
  void setParts(int parts);
  // The split of the last factor's supernodes between threads (its works are entries of L).
  const SubtreePartition& partition() const { return partition_; }

  // Finds L's supernodes and splits them between the threads, unless done since the last invalidate().
  void prepare(const cholmod_factor& L);
  // x = L^-T D^-1 y; x and y may be the same array.
  void solve(const cholmod_factor& L, const double* y, double* x);

 private:
  int supernodeCount() const { return static_cast<int>(first_.empty() ? 0 : first_.size() - 1); }
  void findSupernodes(const cholmod_factor& L);
  void partitionSupernodes(const cholmod_factor& L);
  void substitute(const cholmod_factor& L, const std::vector<int>& supernodes, double* t, double* x) const;
  static void subtractBelow(const cholmod_factor& L, int f, int l, const double* t, int m, double* x);

  std::vector<int> first_;  // the first column of each supernode, then n
  int parts_ = 1;
  SubtreePartition partition_;
  std::vector<std::vector<double>> gathered_;  // one buffer per part
};

}  // namespace tvf
