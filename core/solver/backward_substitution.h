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
// the faster backward substitution; natively CHOLMOD's, compiled for the machine, stays ahead (BackwardKernel
// in solver/factored_system.h).
//
// Diagonal updates keep L's pattern (the path of a column with one entry lies in L's pattern), so the
// supernodes found after a factorization stay valid until the next one.
#include <cholmod.h>

#include <vector>

namespace tvf {

class BackwardSubstitution {
 public:
  // Forgets the supernodes: L's pattern is about to change (a factorization).
  void invalidate();

  // x = L^-T D^-1 y; x and y may be the same array.
  void solve(const cholmod_factor& L, const double* y, double* x);

 private:
  int supernodeCount() const { return static_cast<int>(first_.empty() ? 0 : first_.size() - 1); }
  void findSupernodes(const cholmod_factor& L);
  static void subtractBelow(const cholmod_factor& L, int f, int l, const double* t, int m, double* x);

  std::vector<int> first_;  // the first column of each supernode, then n
  std::vector<double> gathered_;
};

}  // namespace tvf
