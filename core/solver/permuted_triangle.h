#pragma once
// One triangle of P A P', column by column, from A's upper triangle: what the symbolic analysis walks (the
// upper for the elimination tree and the supernodes' rows, the lower for the column counts) and what each
// supernode assembles its columns from (the lower, with values). CHOLMOD permutes by transposing twice on
// one thread; this places each entry once, on `parts` threads.
#include <cholmod.h>

#include <vector>

namespace tvf {

enum class Triangle { Lower, Upper };

// Column j's rows are i[p[j] .. p[j+1]), unsorted (in the order of A's columns); x: their values, or empty
// for the pattern alone. The same arrays whatever the number of threads that made them.
struct PermutedTriangle {
  std::vector<int> p, i;
  std::vector<double> x;
};

// A: symmetric, upper triangle stored (column j: rows <= j); inverse: the inverse of the fill-reducing
// permutation (A's row r goes to row inverse[r]). values: whether x is filled (A.x is read then).
PermutedTriangle permutedTriangle(const cholmod_sparse& A, const std::vector<int>& inverse, Triangle which,
                                  bool values, int parts);

// A pattern view for CHOLMOD's symbolic routines (stype +1 for the upper triangle, -1 for the lower).
cholmod_sparse patternView(PermutedTriangle& t, Triangle which);

}  // namespace tvf
