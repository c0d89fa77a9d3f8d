#include "common/sparse_matrix.h"

namespace tvf {

SparseMatrix upperTriangle(const SparseMatrix& symmetric) {
  SparseMatrix upper = symmetric.triangularView<Eigen::Upper>();
  upper.makeCompressed();
  return upper;
}

SparseMatrix fullFromUpper(const SparseMatrix& upper) {
  SparseMatrix full = upper.selfadjointView<Eigen::Upper>();
  full.makeCompressed();
  return full;
}

}  // namespace tvf
