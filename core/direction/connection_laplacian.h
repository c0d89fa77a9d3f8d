#pragma once
// The smoothness energy of an N-direction field as a power field u_f = e^{i N theta_f} on faces:
// E(u) = sum over interior edges w_fg |u_f - r_fg u_g|^2 with r_fg = e^{i N angle_fg} (the connection raised
// to the N-th power). Its Hermitian matrix H (H_ff = sum w, H_fg = -w r_fg) enters CHOLMOD, which is real, as
// the symmetric [[Re H, -Im H], [Im H, Re H]] with each face's real and imaginary parts interleaved (rows 2f,
// 2f+1), positive (semi)definite exactly when H is.
#include <Eigen/Core>
#include <cstdint>

#include "common/sparse_matrix.h"
#include "dec/hodge_star.h"
#include "direction/levi_civita_connection.h"

namespace tvf {

SparseMatrix connectionLaplacian(const FaceConnection& connection, int32_t numFaces, int symmetry);

// The area mass of a face field in the same interleaved layout: A_f on rows 2f and 2f+1.
Eigen::VectorXd powerFieldMass(const MeshGeometry& geometry);

}  // namespace tvf
