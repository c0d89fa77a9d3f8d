#pragma once
// A view of a numeric supernodal factor's arrays (CHOLMOD's layout): supernode s holds columns
// super[s] .. super[s+1]-1, its rows are ls[pi[s] .. pi[s+1]) (its own columns first, ascending), and its
// values the column-major nsrow x nscol block at x + px[s]. The factorization writes through x; the solves
// only read.
#include <cholmod.h>

namespace tvf {

struct Supernodes {
  int n, count;
  const int *super, *pi, *px, *ls;
  double* x;
  int first(int s) const { return super[s]; }
  int cols(int s) const { return super[s + 1] - super[s]; }
  int rows(int s) const { return pi[s + 1] - pi[s]; }
  const int* rowsOf(int s) const { return ls + pi[s]; }
  double* block(int s) const { return x + px[s]; }
};

inline Supernodes supernodesOf(const cholmod_factor& L) {
  return {static_cast<int>(L.n),         static_cast<int>(L.nsuper),    static_cast<const int*>(L.super),
          static_cast<const int*>(L.pi), static_cast<const int*>(L.px), static_cast<const int*>(L.s),
          static_cast<double*>(L.x)};
}

}  // namespace tvf
