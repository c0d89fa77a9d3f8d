#pragma once
// The sparse matrix type of every operator and system: column-major with int indices, the layout CHOLMOD
// reads without copying (solver/factored_system.cpp views it as a cholmod_sparse).
#include <Eigen/SparseCore>

namespace tvf {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

}  // namespace tvf
