// The field module: Whitney reconstruction against fields it must reproduce exactly, the Hodge
// decomposition's orthogonality, and singularity indices against the Poincare-Hopf theorem.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "dec/exterior_derivative.h"
#include "design/designer.h"
#include "field/hodge_decomposition.h"
#include "field/whitney_reconstruction.h"
#include "mesh/mesh_checks.h"
#include "mesh/mesh_geometry.h"
#include "test_fields.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

TEST(Reconstruction, ConstantFieldIsReproducedExactlyEverywhereInEveryTriangle) {
  SurfaceMesh m = flatGrid(6, 1.0, true);
  jitterPlanar(m, 0.03, 11);
  const MeshTopology t = buildTopology(m);
  const Eigen::Vector3d u(0.4, -1.3, 0);
  std::vector<double> c(t.numEdges);
  for (int e = 0; e < t.numEdges; ++e) c[e] = u.dot(edgeVector(m, t, e));
  const double samples[4][3] = {{1, 0, 0}, {0.2, 0.5, 0.3}, {1.0 / 3, 1.0 / 3, 1.0 / 3}, {0, 0.5, 0.5}};
  for (int f = 0; f < t.numFaces; ++f)
    for (const auto& b : samples) EXPECT_LT((whitneyVector(m, t, c.data(), f, b) - u).norm(), 1e-13);
  const MeshGeometry g = computeMeshGeometry(m, t);
  std::vector<double> vertexField;
  vertexVectors(m, t, g, c.data(), vertexField);
  for (int v = 0; v < t.numVertices; ++v)
    EXPECT_LT((Eigen::Map<const Eigen::Vector3d>(&vertexField[3 * v]) - u).norm(), 1e-13);
}

// The precomputed maps against Eq. 5 written out (the Whitney vector at each corner, whitneyVector at bary =
// that corner, averaged with the corner areas) and Eq. 4 at the barycentre. A torus (curved, every vertex
// interior), an annulus (boundary vertices), with an arbitrary 1-form, and a torus big enough (52k faces) for
// the maps to run in two parts (on the helper threads), where the vertex sums are also made in one part (a
// scratch array too small for the parts' partial sums) and must agree.
TEST(Reconstruction, PrecomputedMapsAreEquations4And5) {
  for (const SurfaceMesh& m :
       {torus(14, 9, 1.0, 0.35), flatAnnulus(4, 24, 0.5, 1.0), torus(200, 130, 1.0, 0.35)}) {
    const MeshTopology t = buildTopology(m);
    const MeshGeometry g = computeMeshGeometry(m, t);
    std::vector<double> c(t.numEdges);
    for (int e = 0; e < t.numEdges; ++e) c[e] = std::sin(1.7 * e) + 0.3 * std::cos(0.2 * e * e);
    std::vector<Eigen::Vector3d> sum(t.numVertices, Eigen::Vector3d::Zero());
    std::vector<double> weight(t.numVertices, 0.0);
    for (int f = 0; f < t.numFaces; ++f)
      for (int k = 0; k < 3; ++k) {
        double bary[3] = {0, 0, 0};
        bary[k] = 1;
        const int32_t v = m.triangles[3 * f + k];
        sum[v] += g.cornerArea[3 * f + k] * whitneyVector(m, t, c.data(), f, bary);
        weight[v] += g.cornerArea[3 * f + k];
      }
    std::vector<double> vertexField;
    vertexVectors(vertexVectorMap(m, t, g), faceVectorMap(m, t), m, t, g, c.data(), vertexField);
    ASSERT_EQ(vertexField.size(), 3 * static_cast<size_t>(t.numVertices));
    double largest = 0, error = 0;
    for (int v = 0; v < t.numVertices; ++v) {
      const Eigen::Vector3d expected = sum[v] / weight[v];
      largest = std::max(largest, expected.norm());
      error = std::max(error, (Eigen::Map<const Eigen::Vector3d>(&vertexField[3 * v]) - expected).norm());
    }
    EXPECT_GT(largest, 0.1);
    EXPECT_LT(error, 1e-12 * largest);
    std::vector<double> onePart, noScratch;
    vertexVectors(vertexVectorMap(m, t, g), faceVectorMap(m, t), m, t, g, c.data(), onePart, noScratch);
    ASSERT_EQ(onePart.size(), vertexField.size());
    for (size_t i = 0; i < onePart.size(); ++i) EXPECT_NEAR(onePart[i], vertexField[i], 1e-13 * largest);
    // Face vectors through their map: Eq. 4 at the barycentre.
    const double centre[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
    std::vector<double> faceField;
    faceVectors(faceVectorMap(m, t), t, c.data(), faceField);
    ASSERT_EQ(faceField.size(), 3 * static_cast<size_t>(t.numFaces));
    largest = error = 0;
    for (int f = 0; f < t.numFaces; ++f) {
      const Eigen::Vector3d expected = whitneyVector(m, t, c.data(), f, centre);
      largest = std::max(largest, expected.norm());
      error = std::max(error, (Eigen::Map<const Eigen::Vector3d>(&faceField[3 * f]) - expected).norm());
    }
    EXPECT_GT(largest, 0.1);
    EXPECT_LT(error, 1e-12 * largest);
  }
}

TEST(Reconstruction, TextureDomainVersionIsTheOneFormsDualInUVSpace) {
  // UV = an affine image of the plane. The 1-form u.dx becomes (J^-T u).duv in UV space, so Eq. 4 with UV
  // quantities gives J^-T u (the push-forward J u itself when J is conformal).
  SurfaceMesh m = flatGrid(4, 1.0, true);
  Eigen::Matrix2d J;
  J << 0.5, 0.2, -0.1, 0.7;
  for (int f = 0; f < m.numFaces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2d p(m.positions[3 * m.triangles[3 * f + c]],
                              m.positions[3 * m.triangles[3 * f + c] + 1]);
      const Eigen::Vector2d q = J * p;
      m.cornerUVs.push_back(float(q.x()));
      m.cornerUVs.push_back(float(q.y()));
    }
  const MeshTopology t = buildTopology(m);
  const Eigen::Vector3d u(1.0, 0.5, 0);
  std::vector<double> c(t.numEdges);
  for (int e = 0; e < t.numEdges; ++e) c[e] = u.dot(edgeVector(m, t, e));
  const Eigen::Vector2d expected = J.inverse().transpose() * u.head<2>();
  const double centre[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  for (int f = 0; f < t.numFaces; ++f)
    EXPECT_LT((whitneyTextureVector(m, t, c.data(), f, centre) - expected).norm(), 1e-6);
}

TEST(Hodge, PartsAreOrthogonalAndHaveTheRightCurlAndDivergence) {
  const SurfaceMesh m = torus(16, 10, 2, 0.7);
  Designer d(m);
  d.addSource(0, 1.0);
  d.addVortex(77, 1.0);
  const double u[3] = {0, 0, 1};
  d.addVector(150, u, 10.0);
  d.solve();
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  const SparseMatrix d0 = exteriorDerivative0(t), d1 = exteriorDerivative1(t);
  const Eigen::VectorXd c = asVector(d.oneForm());
  const HodgeDecomposition h = hodgeDecompose(d0, d1, g, c);
  const auto inner = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return a.dot(h.metric.asDiagonal() * b);
  };
  const double n2 = inner(c, c);
  EXPECT_LT(std::abs(inner(h.exact, h.coexact)) / n2, 1e-9);
  EXPECT_LT(std::abs(inner(h.exact, h.harmonic)) / n2, 1e-9);
  EXPECT_LT(std::abs(inner(h.coexact, h.harmonic)) / n2, 1e-9);
  EXPECT_LT((d1 * h.exact).norm(), 1e-12 * c.norm());  // curl-free
  EXPECT_LT((d0.transpose() * (h.metric.asDiagonal() * h.coexact)).norm(),
            1e-9 * c.norm());  // divergence-free
  EXPECT_LT((d1 * h.harmonic).norm(), 1e-9 * c.norm());
  EXPECT_GT(inner(h.harmonic, h.harmonic) / n2,
            1e-4);  // a torus has harmonic fields and the vector asks for one
}

TEST(Singularities, IndicesSumToTheEulerCharacteristic) {
  struct Case {
    SurfaceMesh mesh;
    int chi;
  };
  const std::vector<Case> cases = {
      {icosphere(3), 2}, {torus(32, 16, 2, 0.7), 0}, {holedPlate(7, 3, {{1, 1}, {3, 1}, {5, 1}}, 3), -4}};
  for (const Case& c : cases) {
    Designer d(c.mesh);
    const int nF = c.mesh.numFaces();
    d.addSource(c.mesh.triangles[0], 1.0);
    d.addVortex(nF / 3, 0.7);
    const double u[3] = {1, 0.2, 0.3};
    d.addVector(2 * nF / 3, u, 10.0);
    d.solve();
    double sum = 0;
    for (const auto& s : d.singularities()) sum += s.index;
    EXPECT_EQ(sum, c.chi) << "singularities: " << d.singularities().size();
  }
}
