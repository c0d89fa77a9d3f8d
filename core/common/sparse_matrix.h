#pragma once
// The sparse matrix type of every operator and system: column-major with int indices, the layout CHOLMOD
// reads without copying (solver/factored_system.cpp views it as a cholmod_sparse).
#include <Eigen/SparseCore>

namespace tvf {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// The systems' symmetric matrices are kept as their upper triangle (diagonal included), the half CHOLMOD
// reads: stored once instead of twice, and never copied to be factored (at 1.25M edges the 1-form Laplacian
// is 85 MB this way; the full matrix and its upper copy for CHOLMOD took 2.5x that at the factorization's
// memory peak).
SparseMatrix upperTriangle(const SparseMatrix& symmetric);
SparseMatrix fullFromUpper(const SparseMatrix& upper);

// Eigen 3.4's SparseMatrix has no move operations: assigning a matrix just made copies it, and assigning an
// empty one keeps the old one's storage. These take a matrix without a copy (`made` is left with the old
// one) and give a matrix's storage back (armadillo-sub2's 1-form Laplacian, 90 MB, was copied once and its
// operators twice at every assembly).
inline void takeMatrix(SparseMatrix& into, SparseMatrix& made) {
  into.swap(made);
}
inline void releaseMatrix(SparseMatrix& m) {
  SparseMatrix empty;
  m.swap(empty);
}

}  // namespace tvf
