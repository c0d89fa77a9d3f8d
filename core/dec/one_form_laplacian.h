#pragma once
// The 1-form Laplacian M = d1' *2 d1 + *1 d0 *0^-1 d0' *1 (Eq. 1), assembled as a sum of weighted Gram
// matrices of d1 and the divergence, with the boundary modifications of Sec. 4.2, and the bi-Laplacian of
// Sec. 6.3.
#include <Eigen/Core>
#include <vector>

#include "dec/exterior_derivative.h"
#include "dec/hodge_star.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct OneFormOperators {
  SparseMatrix d1;
  // Divergence operator D (|V| x |E|): d0' *1, plus the half boundary fluxes for free boundaries; for
  // fixed-angle boundaries its boundary-vertex rows are empty. Right-hand sides of sources use it too.
  SparseMatrix divergence;
  // Fixed-angle rows c_ij cos(b) + f_ij sin(b) (one per boundary edge; empty for free boundaries).
  SparseMatrix boundaryRows;

  OneFormOperators() = default;
  // Moved by swapping the matrices (takeMatrix, common/sparse_matrix.h), where Eigen would copy them; a
  // default one assigned gives the storage back.
  OneFormOperators(OneFormOperators&& other) noexcept { swap(other); }
  OneFormOperators& operator=(OneFormOperators&& other) noexcept {
    OneFormOperators old;
    old.swap(other);
    swap(old);
    return *this;
  }
  void swap(OneFormOperators& other) noexcept {
    d1.swap(other.d1);
    divergence.swap(other.divergence);
    boundaryRows.swap(other.boundaryRows);
  }
};

// angles: per-edge beta (NaN on interior edges), or empty for free boundaries.
OneFormOperators buildOneFormOperators(const SurfaceMesh& mesh, const MeshTopology& topology,
                                       const MeshGeometry& geometry, const std::vector<double>& angles);

// d1' *2 d1 + D' *0^-1 D.
SparseMatrix oneFormLaplacian(const OneFormOperators& ops, const MeshGeometry& geometry);
// Its upper triangle (common/sparse_matrix.h), assembled as such: no product temporaries, no lower half (the
// products took the assembly to 1.1 GB of wasm heap at 1.25M edges, for a 85 MB result).
SparseMatrix oneFormLaplacianUpper(const OneFormOperators& ops, const MeshGeometry& geometry);

// The upper triangle of sum_t K_t' diag(w_t) K_t (every K_t with the same columns; exact zeros dropped, the
// diagonal always stored).
struct GramTerm {
  const SparseMatrix* K;
  const Eigen::VectorXd* w;
};
SparseMatrix upperWeightedGram(const std::vector<GramTerm>& terms);

// The upper triangle of M + gamma M P^-1 M with P the (strictly positive) Whitney 1-form mass diagonal: *1
// may be zero or negative. M: the whole symmetric matrix (oneFormLaplacian).
SparseMatrix biLaplacianUpper(const SparseMatrix& M, const MeshGeometry& geometry, double gamma);

double meanDiagonal(const SparseMatrix& A);

}  // namespace tvf
