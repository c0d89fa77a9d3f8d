#include "dec/one_form_laplacian.h"

#include <cmath>

namespace tvf {
namespace {

using Triplets = std::vector<Eigen::Triplet<double, int>>;

// The inward flux across boundary edge (v_c -> v_a) of face f, f = c_jk cot(i) - c_ki cot(j) (Sec. 4.1),
// written as coefficients on the face's other two edges in their canonical orientation.
struct FluxStencil {
  int32_t edge[2];
  double coefficient[2];
};

FluxStencil boundaryFlux(const MeshTopology& t, const MeshGeometry& g, int32_t f, int c) {
  const int a = (c + 1) % 3, b = (c + 2) % 3;
  const double* cot = &g.cornerCot[3 * f];
  return {{t.edgeOf(f, a), t.edgeOf(f, b)}, {cot[c] * t.signOf(f, a), -cot[a] * t.signOf(f, b)}};
}

SparseMatrix divergenceOperator(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                                const SparseMatrix& d0, bool freeBoundary) {
  SparseMatrix D = d0.transpose() * g.star1.asDiagonal();
  if (freeBoundary) {
    Triplets extra;
    for (int32_t f = 0; f < t.numFaces; ++f)
      for (int c = 0; c < 3; ++c) {
        if (!t.isBoundaryEdge[t.edgeOf(f, c)]) continue;
        const FluxStencil flux = boundaryFlux(t, g, f, c);
        for (const int corner : {c, (c + 1) % 3})
          for (int k = 0; k < 2; ++k)
            extra.emplace_back(mesh.triangles[3 * f + corner], flux.edge[k], 0.5 * flux.coefficient[k]);
      }
    SparseMatrix X(t.numVertices, t.numEdges);
    X.setFromTriplets(extra.begin(), extra.end());
    D += X;
  } else {
    Eigen::VectorXd interior(t.numVertices);
    for (int32_t v = 0; v < t.numVertices; ++v) interior[v] = t.isBoundaryVertex[v] ? 0.0 : 1.0;
    D = interior.asDiagonal() * D;
  }
  D.prune(0.0);
  return D;
}

SparseMatrix fixedAngleRows(const MeshTopology& t, const MeshGeometry& g, const std::vector<double>& angles) {
  Triplets entries;
  int32_t row = 0;
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int c = 0; c < 3; ++c) {
      const int32_t e = t.edgeOf(f, c);
      if (!t.isBoundaryEdge[e]) continue;
      const double beta = angles[e];
      const FluxStencil flux = boundaryFlux(t, g, f, c);
      entries.emplace_back(row, e, std::cos(beta) * t.signOf(f, c));
      for (int k = 0; k < 2; ++k)
        entries.emplace_back(row, flux.edge[k], std::sin(beta) * flux.coefficient[k]);
      ++row;
    }
  SparseMatrix Z(row, t.numEdges);
  Z.setFromTriplets(entries.begin(), entries.end());
  Z.prune(1e-300, 1.0);
  return Z;
}

}  // namespace

OneFormOperators buildOneFormOperators(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                                       const std::vector<double>& angles) {
  OneFormOperators ops;
  ops.d0 = exteriorDerivative0(t);
  ops.d1 = exteriorDerivative1(t);
  const bool freeBoundary = angles.empty();
  ops.divergence = divergenceOperator(mesh, t, g, ops.d0, freeBoundary);
  ops.boundaryRows = freeBoundary ? SparseMatrix(0, t.numEdges) : fixedAngleRows(t, g, angles);
  return ops;
}

SparseMatrix oneFormLaplacian(const OneFormOperators& ops, const MeshGeometry& g) {
  const SparseMatrix curl = ops.d1.transpose() * g.star2.asDiagonal() * ops.d1;
  const Eigen::VectorXd inverseStar0 = g.star0.cwiseInverse();
  const SparseMatrix div = ops.divergence.transpose() * inverseStar0.asDiagonal() * ops.divergence;
  SparseMatrix M = curl + div;
  M.prune(0.0);
  return M;
}

SparseMatrix biLaplacian(const SparseMatrix& M, const MeshGeometry& g, double gamma) {
  const Eigen::VectorXd inverseMass = g.whitneyMass1.cwiseInverse();
  SparseMatrix B = M * inverseMass.asDiagonal() * M;
  SparseMatrix result = M + gamma * B;
  result.prune(0.0);
  return result;
}

double meanDiagonal(const SparseMatrix& A) {
  return A.rows() > 0 ? A.diagonal().sum() / A.rows() : 1.0;
}

}  // namespace tvf
