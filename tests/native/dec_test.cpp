// DEC operators and the 1-form Laplacian against exact invariants.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "dec/exterior_derivative.h"
#include "dec/hodge_star.h"
#include "dec/one_form_laplacian.h"
#include "mesh/mesh_checks.h"
#include "mesh/mesh_geometry.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

struct Built {
  SurfaceMesh mesh;
  MeshTopology topology;
  MeshGeometry geometry;
};

Built build(SurfaceMesh mesh) {
  const MeshReport report = checkMesh(mesh);
  EXPECT_TRUE(report.usable()) << report.firstFatal();
  Built b{mesh, *report.topology, {}};
  b.geometry = computeMeshGeometry(b.mesh, b.topology);
  return b;
}

// The plain M (no boundary modification: every vertex in the divergence term).
SparseMatrix plainLaplacian(const Built& b) {
  OneFormOperators ops;
  const SparseMatrix d0 = exteriorDerivative0(b.topology);
  ops.d1 = exteriorDerivative1(b.topology);
  ops.divergence = d0.transpose() * b.geometry.star1.asDiagonal();
  return oneFormLaplacian(ops, b.geometry);
}

Eigen::VectorXd sampleConstantField(const Built& b, const Eigen::Vector3d& u) {
  Eigen::VectorXd c(b.topology.numEdges);
  for (int e = 0; e < b.topology.numEdges; ++e) c[e] = u.dot(edgeVector(b.mesh, b.topology, e));
  return c;
}

int countNearZeroEigenvalues(const SparseMatrix& M, double& minEigenvalue) {
  const Eigen::MatrixXd dense(M);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& ev = eig.eigenvalues();
  minEigenvalue = ev.minCoeff();
  const double tol = 1e-9 * ev.maxCoeff();
  int count = 0;
  for (int k = 0; k < ev.size(); ++k) count += std::abs(ev[k]) < tol;
  return count;
}

}  // namespace

TEST(ExteriorDerivative, D1TimesD0IsExactlyZero) {
  for (const SurfaceMesh& m :
       {torus(12, 8, 2, 0.7), holedPlate(5, 3, {{1, 1}, {3, 1}}, 2), flatGrid(6, 1, true)}) {
    const Built b = build(m);
    const SparseMatrix product = exteriorDerivative1(b.topology) * exteriorDerivative0(b.topology);
    EXPECT_EQ(SparseMatrix(product.pruned(0.0)).nonZeros(), 0);
  }
}

TEST(OneFormLaplacian, SymmetricWithElevenNonzerosPerRowOnARegularMesh) {
  const Built b = build(torus(24, 16, 2, 0.7));  // valence 6 everywhere
  const SparseMatrix M = plainLaplacian(b);
  const SparseMatrix Mt = M.transpose();
  const double asymmetry = (Eigen::MatrixXd(M) - Eigen::MatrixXd(Mt)).cwiseAbs().maxCoeff();
  EXPECT_LT(asymmetry, 1e-13 * meanDiagonal(M));
  const double perRow = double(M.nonZeros()) / M.rows();
  EXPECT_NEAR(perRow, 11.0, 1.0) << perRow;
}

// d1' *2 d1 + D' *0^-1 D as Eigen's sparse products of the operators: the truth the assembly is checked
// against.
SparseMatrix laplacianProducts(const Built& b, const OneFormOperators& ops) {
  const Eigen::VectorXd inverseStar0 = b.geometry.star0.cwiseInverse();
  return SparseMatrix(ops.d1.transpose() * b.geometry.star2.asDiagonal() * ops.d1) +
         SparseMatrix(ops.divergence.transpose() * inverseStar0.asDiagonal() * ops.divergence);
}

// The Laplacian is assembled as its upper triangle, column by column (upperWeightedGram); checked against
// Eigen's products of the same operators (the sum d1' *2 d1 + D' *0^-1 D, the free boundary's fluxes in D
// included), and a Gram matrix of a random operator against the dense product.
TEST(OneFormLaplacian, UpperTriangleAssemblyEqualsTheProducts) {
  Built b = build(flatGrid(12, 2.0, true));
  jitterPlanar(b.mesh, 0.04, 3);
  b.geometry = computeMeshGeometry(b.mesh, b.topology);
  const OneFormOperators ops = buildOneFormOperators(b.mesh, b.topology, b.geometry, {});
  const SparseMatrix products = laplacianProducts(b, ops);
  const SparseMatrix upper = oneFormLaplacianUpper(ops, b.geometry);
  const Eigen::MatrixXd expected = Eigen::MatrixXd(products).triangularView<Eigen::Upper>();
  EXPECT_LT((Eigen::MatrixXd(upper) - expected).cwiseAbs().maxCoeff(), 1e-12 * meanDiagonal(products));
  for (int j = 0; j < upper.outerSize(); ++j) {  // upper only, every diagonal stored last in its column
    ASSERT_GT(upper.outerIndexPtr()[j + 1], upper.outerIndexPtr()[j]);
    EXPECT_EQ(upper.innerIndexPtr()[upper.outerIndexPtr()[j + 1] - 1], j);
  }
  EXPECT_LT(
      (Eigen::MatrixXd(oneFormLaplacian(ops, b.geometry)) - Eigen::MatrixXd(products)).cwiseAbs().maxCoeff(),
      1e-12 * meanDiagonal(products));

  std::srand(5);
  const Eigen::MatrixXd K =
      Eigen::MatrixXd::Random(9, 7).unaryExpr([](double v) { return v > 0.3 ? v : 0.0; });
  const Eigen::VectorXd w = Eigen::VectorXd::Random(9).cwiseAbs();
  const SparseMatrix Ks = K.sparseView();
  const Eigen::MatrixXd gram = K.transpose() * w.asDiagonal() * K;
  const SparseMatrix G = upperWeightedGram({{&Ks, &w}, {&Ks, &w}});
  const Eigen::MatrixXd twiceUpper = 2.0 * Eigen::MatrixXd(gram.triangularView<Eigen::Upper>());
  EXPECT_LT((Eigen::MatrixXd(G) - twiceUpper).cwiseAbs().maxCoeff(), 1e-14);
}

// Past 100k edges the columns are assembled in parts on the helper threads: the products' upper triangle to
// round-off, with its pattern (every diagonal stored, last in its column).
TEST(OneFormLaplacian, ColumnsAssembledInPartsEqualTheProducts) {
  Built b = build(flatGrid(190, 2.0, true));  // 108,680 edges
  ASSERT_GT(b.topology.numEdges, 100000);
  jitterPlanar(b.mesh, 0.002, 11);
  b.geometry = computeMeshGeometry(b.mesh, b.topology);
  const OneFormOperators ops = buildOneFormOperators(b.mesh, b.topology, b.geometry, {});
  const SparseMatrix products = laplacianProducts(b, ops);
  const SparseMatrix expected = SparseMatrix(products.triangularView<Eigen::Upper>());
  const SparseMatrix upper = oneFormLaplacianUpper(ops, b.geometry);
  EXPECT_LT(SparseMatrix(upper - expected).coeffs().cwiseAbs().maxCoeff(), 1e-12 * meanDiagonal(products));
  for (int j = 0; j < upper.outerSize(); ++j) {
    ASSERT_GT(upper.outerIndexPtr()[j + 1], upper.outerIndexPtr()[j]);
    EXPECT_EQ(upper.innerIndexPtr()[upper.outerIndexPtr()[j + 1] - 1], j);
  }
  EXPECT_EQ(upper.nonZeros(),
            SparseMatrix(expected.pruned(0.0)).nonZeros() + (upper.diagonal().array() == 0.0).count());
}

// gamma's bi-Laplacian M + gamma M P^-1 M, assembled as its upper triangle through the weighted Gram matrix:
// against Eigen's products of the same matrices, on a torus (closed) and on a jittered grid (free boundary).
TEST(OneFormLaplacian, BiLaplacianUpperTriangleEqualsTheProducts) {
  for (const bool closed : {true, false}) {
    Built b = build(closed ? torus(24, 12, 2.0, 0.7) : flatGrid(12, 2.0, true));
    if (!closed) {
      jitterPlanar(b.mesh, 0.04, 5);
      b.geometry = computeMeshGeometry(b.mesh, b.topology);
    }
    const SparseMatrix M =
        oneFormLaplacian(buildOneFormOperators(b.mesh, b.topology, b.geometry, {}), b.geometry);
    const double gamma = 0.1 * b.geometry.totalArea;
    const Eigen::VectorXd inverseMass = b.geometry.whitneyMass1.cwiseInverse();
    const Eigen::MatrixXd truth =
        Eigen::MatrixXd(M) + gamma * (Eigen::MatrixXd(M) * inverseMass.asDiagonal() * Eigen::MatrixXd(M));
    const Eigen::MatrixXd upper = Eigen::MatrixXd(biLaplacianUpper(M, b.geometry, gamma));
    const Eigen::MatrixXd expected = truth.triangularView<Eigen::Upper>();
    EXPECT_LT((upper - expected).cwiseAbs().maxCoeff(), 1e-12 * truth.diagonal().cwiseAbs().maxCoeff())
        << closed;
  }
}

TEST(OneFormLaplacian, ConstantFieldOnAFlatMeshHasZeroEnergyWithFreeBoundary) {
  Built b = build(flatGrid(10, 2.0, true));
  jitterPlanar(b.mesh, 0.04, 7);
  b.geometry = computeMeshGeometry(b.mesh, b.topology);
  const Eigen::VectorXd c = sampleConstantField(b, {0.8, -0.3, 0});
  const OneFormOperators ops = buildOneFormOperators(b.mesh, b.topology, b.geometry, {});
  const SparseMatrix Mfree = oneFormLaplacian(ops, b.geometry);
  const double scale = meanDiagonal(Mfree) * c.squaredNorm();
  EXPECT_LT(std::abs(c.dot(Mfree * c)) / scale, 1e-13);
  EXPECT_LT((Mfree * c).norm() / (meanDiagonal(Mfree) * c.norm()), 1e-13);
  // The unmodified M sees the missing boundary flux: the same field has energy there.
  const SparseMatrix Mplain = plainLaplacian(b);
  EXPECT_GT(c.dot(Mplain * c) / scale, 1e-3);
}

TEST(OneFormLaplacian, ConstantFieldHasZeroEnergyInTheInteriorOfAFlatMesh) {
  Built b = build(flatGrid(8, 1.0, false));
  const Eigen::VectorXd c = sampleConstantField(b, {0.2, 1.0, 0});
  const SparseMatrix M = plainLaplacian(b);
  const Eigen::VectorXd r = M * c;
  for (int e = 0; e < b.topology.numEdges; ++e) {
    const int i = b.topology.edgeVertices[2 * e], j = b.topology.edgeVertices[2 * e + 1];
    if (!b.topology.isBoundaryVertex[i] && !b.topology.isBoundaryVertex[j])
      EXPECT_NEAR(r[e], 0.0, 1e-12 * meanDiagonal(M)) << "edge " << e;
  }
}

TEST(OneFormLaplacian, KernelDimensionIsTheFirstBettiNumberAndNoEigenvalueIsNegative) {
  struct Case {
    SurfaceMesh mesh;
    int betti;
  };
  const std::vector<Case> cases = {
      {icosphere(1), 0},
      {torus(10, 6, 2, 0.7), 2},
      {holedPlate(5, 3, {{1, 1}, {3, 1}}, 1), 4},
      {holedPlate(7, 3, {{1, 1}, {3, 1}, {5, 1}}, 1), 6},
      {flatAnnulus(2, 12, 1, 2), 1},
      {disjointUnion(torus(8, 6, 2, 0.7), flatAnnulus(2, 10, 1, 2)), 3},
  };
  for (const Case& c : cases) {
    const Built b = build(c.mesh);
    double minEigenvalue = 0;
    const SparseMatrix M = plainLaplacian(b);
    EXPECT_EQ(countNearZeroEigenvalues(M, minEigenvalue), c.betti) << "edges " << b.topology.numEdges;
    EXPECT_GT(minEigenvalue, -1e-9 * meanDiagonal(M));
  }
}

TEST(HodgeStar, Star0IsStrictlyPositiveEvenWhereTheCircumcentricAreaIsNot) {
  // Very obtuse fans: a flat strip squashed so many angles exceed 90 degrees.
  SurfaceMesh m = flatGrid(8, 1.0, true);
  for (int v = 0; v < m.numVertices(); ++v) m.positions[3 * v + 1] *= 0.08;
  jitterPlanar(m, 0.02, 3);
  const Built b = build(m);
  EXPECT_GT(b.geometry.star0.minCoeff(), 0.0);
  EXPECT_GT(b.geometry.positiveAreaFallbackVertices, 0);
  EXPECT_GT(b.geometry.whitneyMass1.minCoeff(), 0.0);
  double minEigenvalue = 0;
  countNearZeroEigenvalues(plainLaplacian(b), minEigenvalue);
  EXPECT_GT(minEigenvalue, -1e-9 * meanDiagonal(plainLaplacian(b)));
}

TEST(HodgeStar, AreasSumToTheSurfaceArea) {
  const Built b = build(icosphere(2));
  double faceSum = 0;
  for (const double a : b.geometry.faceArea) faceSum += a;
  EXPECT_NEAR(b.geometry.star0.sum(), faceSum, 1e-9 * faceSum);
  EXPECT_NEAR(b.geometry.totalArea, faceSum, 1e-12 * faceSum);
}
