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

}  // namespace tvf
