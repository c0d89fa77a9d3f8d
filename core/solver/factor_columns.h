#pragma once
// CHOLMOD's simplicial LDL' factor read column by column, for the kernels that walk L themselves (the kept
// forward substitution, the backward substitution by supernodes, the held update's correction). Each column
// holds its diagonal first, then its rows below it, sorted: in the exact pattern these are the column's
// ancestors in the elimination tree.
#include <cholmod.h>

namespace tvf {

struct FactorColumns {
  const int* p;
  const int* i;
  const int* nz;
  const double* x;
};

inline FactorColumns factorColumns(const cholmod_factor& L) {
  return {static_cast<const int*>(L.p), static_cast<const int*>(L.i), static_cast<const int*>(L.nz),
          static_cast<const double*>(L.x)};
}

// The parent of column j in the elimination tree (-1 at a root): the row of its first entry below the
// diagonal.
inline int parentColumn(const FactorColumns& L, int j) {
  return L.nz[j] > 1 ? L.i[L.p[j] + 1] : -1;
}

// Whether column j + 1 continues j's supernode: it is j's parent and holds j's rows below it, so j has
// exactly one entry more.
inline bool continuesSupernode(const FactorColumns& L, int j) {
  return L.nz[j] == L.nz[j + 1] + 1 && L.i[L.p[j] + 1] == j + 1;
}

}  // namespace tvf
