// Line and cross fields (N-direction fields as power fields; direction/) against truths that do not come from
// the solver: Poincaré–Hopf (indices sum to the Euler characteristic, each a multiple of 1/N), truly
// fractional indices on a generic curved surface, the exactly parallel field of a flat square, a torus's zero
// sum, undo as a downdate equal to a fresh solve, a straight stroke followed on a curved surface, the
// smoothest field as an eigenvector (H u = lambda M u, residual), curvature alignment on a torus of
// revolution (whose principal directions are its parallels and meridians), and the design format and CLI.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "cli_run.h"
#include "common/input_error.h"
#include "constraints/surface_walk.h"
#include "design/design_document.h"
#include "design/designer.h"
#include "direction/connection_laplacian.h"
#include "direction/levi_civita_connection.h"
#include "direction/representative_directions.h"
#include "io/mesh_io.h"
#include "mesh/mesh_geometry.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

double indexSum(const Designer& d) {
  double sum = 0;
  for (const Singularity& s : d.singularities()) sum += s.index;
  return sum;
}

void expectIndicesAreMultiplesOf(const Designer& d, int n) {
  for (const Singularity& s : d.singularities())
    EXPECT_NEAR(s.index * n, std::round(s.index * n), 1e-12) << "vertex " << s.vertex << " index " << s.index;
}

Eigen::Vector3d faceCentre(const SurfaceMesh& m, int32_t f) {
  Eigen::Vector3d p[3];
  facePositions(m, f, p);
  return (p[0] + p[1] + p[2]) / 3;
}

// The face whose centre is nearest to x.
int32_t nearestFace(const SurfaceMesh& m, const Eigen::Vector3d& x) {
  int32_t best = 0;
  for (int32_t f = 1; f < m.numFaces(); ++f)
    if ((faceCentre(m, f) - x).norm() < (faceCentre(m, best) - x).norm()) best = f;
  return best;
}

std::vector<SurfacePoint> centresStroke(const std::vector<int32_t>& faces) {
  std::vector<SurfacePoint> points;
  for (const int32_t f : faces) points.push_back({f, {1.0 / 3, 1.0 / 3, 1.0 / 3}});
  return points;
}

double angleToRepresentative(const Designer& d, int32_t f, const Eigen::Vector3d& wanted) {
  const Eigen::Vector3d rep(&d.faceVectors()[3 * f]);
  const Eigen::Vector3d n(&d.geometry().faceNormal[3 * f]);
  const Eigen::Vector3d w = (wanted - n * n.dot(wanted)).normalized();
  return std::abs(symmetricAngle(rep, w, n, d.symmetry()));
}

}  // namespace

TEST(DirectionField, ConnectionLaplacianIsHermitianAndAnnihilatesParallelFieldsOnAPlane) {
  SurfaceMesh m = flatGrid(6, 1.0, true);
  jitterPlanar(m, 0.03, 3);  // a fifth of a cell: no folds
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  const FaceFrames frames = faceFrames(m, g);
  for (const int n : {1, 2, 4}) {
    const SparseMatrix H = connectionLaplacian(leviCivitaConnection(m, t, g, frames), t.numFaces, n);
    EXPECT_NEAR((SparseMatrix(H.transpose()) - H).norm(), 0, 1e-12);
    // The constant direction 0.3 rad from x, as a power field in each face's frame, is parallel: H u = 0.
    Eigen::VectorXd u(2 * t.numFaces);
    const double dir[3] = {std::cos(0.3), std::sin(0.3), 0};
    for (int32_t f = 0; f < t.numFaces; ++f) {
      const std::complex<double> z = std::pow(inFaceFrame(frames, f, dir), n);
      u[2 * f] = z.real();
      u[2 * f + 1] = z.imag();
    }
    EXPECT_LT((H * u).norm(), 1e-12) << "N = " << n;
  }
}

TEST(DirectionField, IndicesSumToEulerCharacteristicAndAreMultiplesOfOneOverN) {
  const std::vector<std::pair<const char*, SurfaceMesh>> meshes = {
      {"icosphere", icosphere(3)},
      {"bumpy sphere", bumpySphere()},
      {"torus", torus(40, 20, 1.0, 0.35)},
      {"genus 2 plate", holedPlate(3, 2, {{0, 0}, {2, 1}}, 2)}};
  for (const auto& [name, mesh] : meshes) {
    for (const int n : {2, 3, 4, 6}) {
      Designer d(mesh);
      d.setSymmetry(n);
      d.solve();  // the smoothest unconstrained field
      const int chi = d.topology().eulerCharacteristic();
      EXPECT_NEAR(indexSum(d), chi, 1e-9) << name << " N = " << n << " (smoothest)";
      expectIndicesAreMultiplesOf(d, n);
      const double along[3] = {1, 0.2, 0.5};
      d.addVector(7, along, 1.0);
      d.solve();
      EXPECT_NEAR(indexSum(d), chi, 1e-9) << name << " N = " << n << " (one direction)";
      expectIndicesAreMultiplesOf(d, n);
      for (int32_t f = 0; f < d.mesh().numFaces(); ++f)
        EXPECT_NEAR(Eigen::Vector3d(&d.faceVectors()[3 * f]).norm(), 1, 1e-12);
    }
  }
}

TEST(DirectionField, GenericCurvedSurfaceHasTrulyFractionalIndices) {
  for (const int n : {2, 4}) {
    Designer d(bumpySphere());
    d.setSymmetry(n);
    const double along[3] = {0.3, 1, 0.2};
    d.addVector(11, along, 1.0);
    d.solve();
    int fractional = 0;
    for (const Singularity& s : d.singularities())
      fractional += std::abs(s.index - std::round(s.index)) > 1e-9;
    EXPECT_GT(fractional, 0) << "N = " << n;
    if (n == 4) {
      int quarter = 0;
      for (const Singularity& s : d.singularities())
        quarter += std::abs(2 * s.index - std::round(2 * s.index)) > 1e-9;
      EXPECT_GT(quarter, 0) << "a cross field on a generic sphere has indices of +-1/4";
    }
  }
}

TEST(DirectionField, FlatSquareWithOneDirectionIsExactlyConstant) {
  SurfaceMesh m = flatGrid(8, 1.0, true);
  jitterPlanar(m, 0.025, 5);  // a fifth of a cell: no folds
  for (const int n : {2, 4, 5}) {
    Designer d(m);
    d.setSymmetry(n);
    const int32_t f0 = 17;
    // Parallel to one of the face's edges, as the truth asks.
    const Eigen::Vector3d edge = edgeVector(d.mesh(), d.topology(), d.topology().edgeOf(f0, 0));
    d.addVector(f0, edge.data(), 1.0);
    d.solve();
    double worst = 0;
    for (int32_t f = 0; f < d.mesh().numFaces(); ++f)
      worst = std::max(worst, angleToRepresentative(d, f, edge));
    EXPECT_LT(worst, 1e-9) << "N = " << n;
    EXPECT_TRUE(d.singularities().empty());
  }
}

TEST(DirectionField, TorusIndicesSumToZero) {
  for (const int n : {2, 4}) {
    Designer d(torus(48, 16, 1.0, 0.45));
    d.setSymmetry(n);
    const double a[3] = {0, 0, 1}, b[3] = {1, 1, 0};
    d.addVector(3, a, 1.0);
    d.addVector(400, b, 1.0);
    d.solve();
    EXPECT_NEAR(indexSum(d), 0, 1e-9) << "N = " << n;
    expectIndicesAreMultiplesOf(d, n);
  }
}

TEST(DirectionField, UndoOfAStrokeEqualsAFreshSolve) {
  const SurfaceMesh m = bumpySphere();
  for (const int n : {2, 4}) {
    Designer d(m);
    d.setSymmetry(n);
    const auto first = centresStroke(
        {nearestFace(m, {1, 0, 0}), nearestFace(m, {0.9, 0.4, 0}), nearestFace(m, {0.7, 0.7, 0.1})});
    const auto second = centresStroke(
        {nearestFace(m, {0, 0, 1}), nearestFace(m, {0.3, 0.1, 0.9}), nearestFace(m, {0.6, 0.2, 0.7})});
    d.addStroke(first, 1, 10);
    d.solve();
    const int32_t id = d.addStroke(second, 1, 100);
    d.solve();
    d.remove(id);  // undo: the inverse rank update
    d.solve();
    Designer fresh(m);
    fresh.setSymmetry(n);
    fresh.addStroke(first, 1, 10);
    fresh.solve();
    double worst = 0;
    for (int32_t f = 0; f < m.numFaces(); ++f)
      worst = std::max(worst, angleToRepresentative(d, f, Eigen::Vector3d(&fresh.faceVectors()[3 * f])));
    EXPECT_LT(worst, 1e-9) << "N = " << n;
    EXPECT_EQ(d.stats().precisionRefactors, 0);
  }
}

TEST(DirectionField, StraightStrokeIsFollowedOnACurvedSurface) {
  // A stroke along a parallel of a torus (test_meshes' layout: quad (i, j) is faces 2 (j n + i) and +1) at
  // weight 1e4: at every face it crosses, the field is within 1 degree of the stroke's heading there.
  const int n = 64, m = 24;
  const SurfaceMesh mesh = torus(n, m, 1.0, 0.4);
  const std::vector<SurfacePoint> points = torusParallelStroke();
  const MeshTopology t = buildTopology(mesh);
  const StrokeWalk walk = walkStroke(mesh, t, points);
  ASSERT_GT(walk.crossings.size(), 20u);
  for (const int symmetry : {2, 4}) {
    Designer d(mesh);
    d.setSymmetry(symmetry);
    d.addStroke(points, 1, 1e4);
    d.solve();
    double worst = 0;
    for (const StrokeCrossing& c : walk.crossings)
      worst = std::max(worst, angleToRepresentative(d, c.face, c.direction));
    EXPECT_LT(worst * 180 / kPi, 1.0) << "N = " << symmetry;
  }
}

TEST(DirectionField, EditsAreRankUpdatesNeverRefactorizations) {
  // The smoothest field, then strokes in and out, a weight change and a clear: one numeric factorization in
  // all.
  const SurfaceMesh m = bumpySphere(2);
  Designer d(m);
  d.setSymmetry(4);
  d.solve();
  ASSERT_EQ(d.stats().factorizations, 1);
  ASSERT_GT(d.stats().inverseIterations, 0);
  const int32_t a =
      d.addStroke(centresStroke({nearestFace(m, {1, 0, 0}), nearestFace(m, {0.7, 0.7, 0})}), 1, 10);
  d.solve();  // the first stroke switches to the constrained solve with the same factor
  EXPECT_EQ(d.stats().inverseIterations, 0);
  const int32_t b =
      d.addStroke(centresStroke({nearestFace(m, {0, 0, 1}), nearestFace(m, {0.5, 0, 0.8})}), 1, 100);
  d.solve();
  d.setWeight(b, 1000);
  d.solve();
  d.remove(a);
  d.solve();
  d.clearConstraints();
  d.solve();
  EXPECT_EQ(d.stats().factorizations, 1);
  EXPECT_EQ(d.stats().precisionRefactors, 0);
}

TEST(DirectionField, FixedAngleBoundaryHoldsLineAndCrossFields) {
  // A flat annulus: tangential makes the field follow the boundary circles (a line field there is the field
  // of circles: index 0 inside the annulus); normal makes it radial.
  const SurfaceMesh m = flatAnnulus(6, 48, 0.5, 1.0);
  for (const int n : {2, 4}) {
    for (const char* which : {"tangential", "normal"}) {
      Designer d(m);
      d.setSymmetry(n);
      d.setBoundary(boundaryFromJson(which));
      d.solve();
      double worst = 0;
      for (int32_t f = 0; f < m.numFaces(); ++f) {
        const Eigen::Vector3d c = faceCentre(m, f);
        const Eigen::Vector3d circle(-c.y(), c.x(), 0);
        worst = std::max(worst, angleToRepresentative(d, f, std::string(which) == "tangential" ? circle : c));
      }
      EXPECT_LT(worst * 180 / kPi, 1.0) << which << " N = " << n;
      EXPECT_TRUE(d.stats().warnings.empty());
    }
  }
}

TEST(DirectionField, SmoothestFieldIsTheLowestEigenvector) {
  Designer d(bumpySphere(2));
  d.setSymmetry(2);
  d.solve();
  // Rayleigh quotient of the result against that of many random fields: the smoothest is below all.
  const double lambda = d.stats().smoothestEigenvalue;
  EXPECT_GT(lambda, 0);
  EXPECT_GT(d.stats().inverseIterations, 0);
  const FaceFrames frames = faceFrames(d.mesh(), d.geometry());
  const SparseMatrix H = connectionLaplacian(
      leviCivitaConnection(d.mesh(), d.topology(), d.geometry(), frames), d.mesh().numFaces(), 2);
  const Eigen::VectorXd mass = powerFieldMass(d.geometry());
  std::mt19937 rng(4);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd x(H.rows());
    for (Eigen::Index k = 0; k < x.size(); ++k) x[k] = g(rng);
    EXPECT_GT(x.dot(H * x) / x.dot(mass.cwiseProduct(x)), lambda);
  }
  EXPECT_NEAR(indexSum(d), 2, 1e-9);
}

TEST(DirectionField, CurvatureAlignmentFollowsATorusOfRevolutionsPrincipalDirections) {
  const SurfaceMesh m = torus(64, 24, 1.0, 0.4);
  Designer d(m);
  d.setSymmetry(4);
  d.setCurvatureAlignment(1);
  d.solve();
  double sum = 0;
  for (int32_t f = 0; f < m.numFaces(); ++f) {
    const Eigen::Vector3d c = faceCentre(m, f);
    sum += angleToRepresentative(d, f, Eigen::Vector3d(-c.y(), c.x(), 0));  // the parallel through c
  }
  EXPECT_LT(sum / m.numFaces() * 180 / kPi, 2.0);
  EXPECT_TRUE(d.singularities().empty());
}

TEST(DirectionField, VectorNotionsAreRefusedByName) {
  Designer d(icosphere(2));
  d.addSource(0, 1);
  d.addVortex(3, 1);
  try {
    d.setSymmetry(2);
    FAIL() << "a source and a vortex were carried into a line field";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("1 source, 1 vortex"), std::string::npos) << e.what();
  }
  EXPECT_EQ(d.symmetry(), 1);
  d.clearConstraints();
  d.setSymmetry(4);
  EXPECT_THROW(d.addSink(2, 1), InputError);
  EXPECT_THROW(d.addEdge(0, 1, 0.1, 1), InputError);
  EXPECT_THROW(d.hodgeDecomposition(), InputError);
  EXPECT_TRUE(d.constraints().empty()) << "a refused constraint left something behind";
  EXPECT_THROW(d.setSymmetry(7), InputError);
  EXPECT_THROW(d.setSymmetry(0), InputError);
  d.setSymmetry(3);
  EXPECT_THROW(d.setCurvatureAlignment(1), InputError);
}

TEST(DirectionField, SwitchingSymmetryKeepsStrokesAndDirections) {
  const SurfaceMesh m = bumpySphere(2);
  Designer d(m);
  const auto stroke = centresStroke({nearestFace(m, {1, 0, 0}), nearestFace(m, {0.8, 0.5, 0})});
  d.addStroke(stroke, 1, 10);
  const double v[3] = {0, 1, 0};
  d.addVector(nearestFace(m, {0, 0, 1}), v, 5);
  d.solve();
  const std::vector<double> vectorField = d.faceVectors();
  d.setSymmetry(2);
  d.solve();
  EXPECT_EQ(d.constraints().size(), 2u);
  d.setSymmetry(1);
  d.solve();
  EXPECT_EQ(d.faceVectors(), vectorField) << "back to N = 1 the vector field is what it was";
}

TEST(DirectionField, DesignDocumentCarriesSymmetry) {
  const SurfaceMesh m = bumpySphere(2);
  Designer d(m);
  d.setSymmetry(4);
  d.setCurvatureAlignment(0.5);
  const double v[3] = {0, 1, 0};
  d.addVector(5, v, 2);
  const nlohmann::json doc = designDocument(d);
  EXPECT_EQ(doc["symmetry"], 4);
  EXPECT_EQ(doc["curvatureAlignment"], 0.5);
  Designer other(m);
  applyDesignDocument(other, doc);
  EXPECT_EQ(other.symmetry(), 4);
  EXPECT_EQ(other.curvatureAlignment(), 0.5);
  d.solve();
  other.solve();
  EXPECT_EQ(d.faceVectors(), other.faceVectors());
  // A vector design has no symmetry key, as before; a source in a line-field design is refused by name.
  EXPECT_FALSE(designDocument(Designer(m)).contains("symmetry"));
  nlohmann::json bad = doc;
  bad["constraints"].push_back({{"type", "source"}, {"vertex", 0}, {"strength", 1}});
  try {
    applyDesignDocument(other, bad);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("constraint 1"), std::string::npos) << e.what();
  }
  EXPECT_EQ(other.constraints().size(), 1u) << "a refused document left the design changed";
}

#ifdef TVF_CLI_PATH
namespace {
void writeOff(const SurfaceMesh& m, const std::string& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << m.positions.size() / 3 << " " << m.numFaces() << " 0\n";
  for (size_t k = 0; k < m.positions.size(); k += 3)
    out << m.positions[k] << " " << m.positions[k + 1] << " " << m.positions[k + 2] << "\n";
  for (int32_t f = 0; f < m.numFaces(); ++f)
    out << "3 " << m.triangles[3 * f] << " " << m.triangles[3 * f + 1] << " " << m.triangles[3 * f + 2]
        << "\n";
}
}  // namespace

TEST(DirectionField, CliWritesFaceDirectionsAndFractionalIndices) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "tvf-direction-cli";
  std::filesystem::create_directories(dir);
  const SurfaceMesh m = bumpySphere(2);
  writeOff(m, (dir / "sphere.off").string());
  const SurfaceMesh loaded = loadMesh((dir / "sphere.off").string());
  Designer d(loaded);
  d.setSymmetry(2);
  const double v[3] = {0.2, 1, 0.1};
  d.addVector(9, v, 1);
  std::ofstream((dir / "design.json").string()) << designDocument(d).dump();
  const CliRun r = runTvf("design " + (dir / "sphere.off").string() + " " + (dir / "design.json").string() +
                          " -o " + (dir / "field.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  nlohmann::json field;
  std::ifstream((dir / "field.json").string()) >> field;
  EXPECT_EQ(field["symmetry"], 2);
  EXPECT_FALSE(field.contains("oneForm"));
  d.solve();
  ASSERT_EQ(field["faceDirections"].size(), static_cast<size_t>(loaded.numFaces()));
  for (int32_t f = 0; f < loaded.numFaces(); ++f) {
    const auto& r3 = field["faceDirections"][f];
    const Eigen::Vector3d written(r3[0].get<double>(), r3[1].get<double>(), r3[2].get<double>());
    EXPECT_LT(angleToRepresentative(d, f, written), 1e-6);
  }
  double sum = 0;
  bool half = false;
  for (const auto& s : field["singularities"]) {
    sum += s["index"].get<double>();
    half |= std::abs(s["index"].get<double>()) == 0.5;
  }
  EXPECT_NEAR(sum, 2, 1e-12);
  EXPECT_TRUE(half);
  const CliRun bench = runTvf("bench " + (dir / "sphere.off").string() + " --symmetry 4 --json --repeat 1");
  ASSERT_EQ(bench.exitCode, 0) << bench.err;
  const nlohmann::json b = nlohmann::json::parse(bench.out);
  for (const char* key : {"factorMs", "solveMs", "updateMs", "strokeUpdateSolveMs", "smoothestMs"})
    EXPECT_TRUE(b.contains(key)) << key;
  EXPECT_EQ(b["symmetry"], 4);
  const CliRun hodge =
      runTvf("design " + (dir / "sphere.off").string() + " " + (dir / "design.json").string() + " --hodge");
  EXPECT_EQ(hodge.exitCode, 2);
  EXPECT_NE(hodge.err.find("vector fields"), std::string::npos) << hodge.err;
}
#endif

// The page's default model (dist/models/bunny.glb, the Stanford bunny that `npm run build:web` writes from
// the npm `bunny` package; npm test builds it before the native tests): a straight stroke — two points, so
// the walk between them is the surface's discrete straight line — is followed within 1 degree at every face
// it crosses, at weight 1e4, and the indices are multiples of 1/N summing to the Euler characteristic.
TEST(DirectionField, StraightStrokeIsFollowedOnTheBunny) {
  const std::string path = std::string(TVF_TEST_DATA_DIR) + "/../../../dist/models/bunny.glb";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path << " (npm run build:web writes it)";
  const SurfaceMesh mesh = loadMesh(path);
  const MeshTopology t = buildTopology(mesh);
  // From a face on one side of the bunny's bounding box towards one a third of the way across.
  Eigen::Vector3d lo = faceCentre(mesh, 0), hi = lo;
  for (int32_t f = 0; f < mesh.numFaces(); ++f) {
    lo = lo.cwiseMin(faceCentre(mesh, f));
    hi = hi.cwiseMax(faceCentre(mesh, f));
  }
  const Eigen::Vector3d mid = (lo + hi) / 2, size = hi - lo;
  const int32_t a =
      nearestFace(mesh, mid + Eigen::Vector3d(-0.25 * size.x(), 0.1 * size.y(), 0.5 * size.z()));
  const int32_t b = nearestFace(mesh, mid + Eigen::Vector3d(0.1 * size.x(), 0.15 * size.y(), 0.5 * size.z()));
  const std::vector<SurfacePoint> points = centresStroke({a, b});
  const StrokeWalk walk = walkStroke(mesh, t, points);
  ASSERT_GE(walk.crossings.size(), 10u);
  for (const int n : {2, 4}) {
    Designer d(mesh);
    d.setSymmetry(n);
    d.addStroke(points, 1, 1e4);
    d.solve();
    double worst = 0;
    for (const StrokeCrossing& c : walk.crossings)
      worst = std::max(worst, angleToRepresentative(d, c.face, c.direction));
    EXPECT_LT(worst * 180 / kPi, 1.0) << "N = " << n << ", " << walk.crossings.size() << " faces";
    double sum = 0;
    for (const Singularity& s : d.singularities()) sum += s.index;
    expectIndicesAreMultiplesOf(d, n);
    if (d.topology().isBoundaryVertex.end() ==
        std::find(d.topology().isBoundaryVertex.begin(), d.topology().isBoundaryVertex.end(), 1))
      EXPECT_NEAR(sum, d.topology().eulerCharacteristic(), 1e-9);
  }
}
