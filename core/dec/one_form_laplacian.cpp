#include "dec/one_form_laplacian.h"

#include <algorithm>
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

SparseMatrix oneFormLaplacianUpper(const OneFormOperators& ops, const MeshGeometry& g) {
  const Eigen::VectorXd inverseStar0 = g.star0.cwiseInverse();
  return upperWeightedGram({{&ops.d1, &g.star2}, {&ops.divergence, &inverseStar0}});
}

SparseMatrix oneFormLaplacian(const OneFormOperators& ops, const MeshGeometry& g) {
  return fullFromUpper(oneFormLaplacianUpper(ops, g));
}

// Column j of sum_t K_t' W_t K_t is sum over the rows r with K_t(r, j) != 0 of w_r K_t(r, j) K_t(r, :)': one
// pass over the columns with a dense accumulator, written straight into the result's arrays, counted first so
// that nothing is reallocated.
SparseMatrix upperWeightedGram(const std::vector<GramTerm>& terms) {
  using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
  const int n = terms.empty() ? 0 : static_cast<int>(terms[0].K->cols());
  std::vector<RowMajor> rows;
  rows.reserve(terms.size());
  for (const GramTerm& t : terms) rows.emplace_back(*t.K);
  std::vector<double> sum(n, 0.0);
  std::vector<int> seen(n, -1), touched;
  // Visits column j's upper entries (row <= j), leaving their sums in `sum` and rows in `touched`, sorted.
  auto column = [&](int j) {
    touched.clear();
    for (size_t k = 0; k < terms.size(); ++k)
      for (SparseMatrix::InnerIterator it(*terms[k].K, j); it; ++it) {
        const double s = (*terms[k].w)[it.row()] * it.value();
        for (RowMajor::InnerIterator jt(rows[k], it.row()); jt && jt.col() <= j; ++jt) {
          if (seen[jt.col()] != j) {
            seen[jt.col()] = j;
            sum[jt.col()] = 0;
            touched.push_back(jt.col());
          }
          sum[jt.col()] += s * jt.value();
        }
      }
    std::sort(touched.begin(), touched.end());
  };
  auto kept = [&](int i, int j) { return sum[i] != 0.0 || i == j; };  // the diagonal always: it is factored
  SparseMatrix G(n, n);
  Eigen::Index nonZeros = 0;
  for (int j = 0; j < n; ++j) {
    column(j);
    for (const int i : touched) nonZeros += kept(i, j);
  }
  std::fill(seen.begin(), seen.end(), -1);
  G.resizeNonZeros(nonZeros);
  int* outer = G.outerIndexPtr();
  int* inner = G.innerIndexPtr();
  double* values = G.valuePtr();
  int next = 0;
  outer[0] = 0;
  for (int j = 0; j < n; ++j) {
    column(j);
    for (const int i : touched)
      if (kept(i, j)) {
        inner[next] = i;
        values[next++] = sum[i];
      }
    outer[j + 1] = next;
  }
  return G;
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
