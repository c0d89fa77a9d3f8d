// The Hodge decomposition c = d a + delta b + h (Eq. 3; field/hodge_decomposition.h) against truths that do
// not come from it: the parts sum to the field and are orthogonal; d1 d0 = 0 makes the exact part curl-free
// and d0' *1 *1^-1 d1' = (d1 d0)' = 0 the coexact part divergence-free, so what is left must be both; the
// harmonic space has the dimension of the first cohomology (2g on a closed genus-g surface, b - 1 more with
// boundary loops), measured as the kernel of the 1-form Laplacian assembled here from the stars; harmonic
// parts have the same circulation around homologous loops (Stokes with d1 h = 0); designs made only of
// sources and sinks are curl-free, of vortices divergence-free. And `tvf design --hodge` / `tvf export
// --component` as a user runs them.
#include <gtest/gtest.h>
#include <png.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "dec/exterior_derivative.h"
#include "design/design_document.h"
#include "design/designer.h"
#include "design/field_export.h"
#include "field/hodge_decomposition.h"
#include "mesh/mesh_geometry.h"
#include "test_fields.h"
#include "cli_run.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

struct Operators {
  MeshTopology t;
  MeshGeometry g;
  SparseMatrix d0, d1;
  explicit Operators(const SurfaceMesh& m)
      : t(buildTopology(m)), g(computeMeshGeometry(m, t)), d0(exteriorDerivative0(t)), d1(exteriorDerivative1(t)) {}
  HodgeDecomposition decompose(const Eigen::VectorXd& c) const { return hodgeDecompose(d0, d1, g, c); }
};

double inner(const HodgeDecomposition& h, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.dot(h.metric.asDiagonal() * b);
}

Eigen::VectorXd randomOneForm(int edges, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd c(edges);
  for (int e = 0; e < edges; ++e) c[e] = u(rng);
  return c;
}

// Every property of a decomposition that holds for any 1-form on any mesh.
void expectDecomposition(const Operators& o, const Eigen::VectorXd& c, const std::string& what) {
  SCOPED_TRACE(what);
  const HodgeDecomposition h = o.decompose(c);
  const double n2 = inner(h, c, c);
  ASSERT_GT(n2, 0);
  // Sum.
  EXPECT_LE((h.exact + h.coexact + h.harmonic - c).norm(), 1e-10 * c.norm());
  // Pairwise orthogonal in the decomposition's inner product.
  EXPECT_LE(std::abs(inner(h, h.exact, h.coexact)) / n2, 1e-10);
  EXPECT_LE(std::abs(inner(h, h.exact, h.harmonic)) / n2, 1e-10);
  EXPECT_LE(std::abs(inner(h, h.coexact, h.harmonic)) / n2, 1e-10);
  // Curl (d1) and divergence (d0' P) relative to the field's own.
  const Eigen::VectorXd curl = o.d1 * c, divergence = o.d0.transpose() * (h.metric.asDiagonal() * c);
  EXPECT_LE((o.d1 * h.exact).norm(), 1e-8 * curl.norm()) << "curl of the exact part";
  EXPECT_LE((o.d0.transpose() * (h.metric.asDiagonal() * h.coexact)).norm(), 1e-8 * divergence.norm())
      << "divergence of the coexact part";
  EXPECT_LE((o.d1 * h.harmonic).norm(), 1e-8 * curl.norm()) << "curl of the harmonic part";
  EXPECT_LE((o.d0.transpose() * (h.metric.asDiagonal() * h.harmonic)).norm(), 1e-8 * divergence.norm())
      << "divergence of the harmonic part";
  // The exact part takes all the divergence and the coexact all the curl.
  EXPECT_LE((o.d1 * h.coexact - curl).norm(), 1e-8 * curl.norm());
  EXPECT_LE((o.d0.transpose() * (h.metric.asDiagonal() * h.exact) - divergence).norm(), 1e-8 * divergence.norm());
  // The potentials give the parts.
  EXPECT_LE((o.d0 * h.potential0 - h.exact).norm(), 1e-12 * c.norm());
  EXPECT_LE((h.metric.cwiseInverse().asDiagonal() * (o.d1.transpose() * h.potential2) - h.coexact).norm(),
            1e-12 * c.norm());
  const HodgeEnergyShares s = hodgeEnergyShares(h);
  EXPECT_NEAR(s.exact + s.coexact + s.harmonic, 1.0, 1e-10);
}

// The 1-form Laplacian of a closed mesh, d1' *2 d1 + P d0 *0^-1 d0' P, assembled densely from the stars, with
// P = *1 (the product's M) or another positive 1-form inner product. Its kernel: d1 h = 0 and d0' P h = 0.
Eigen::MatrixXd denseLaplacian(const Operators& o, const Eigen::VectorXd& P) {
  const Eigen::MatrixXd D0 = Eigen::MatrixXd(o.d0), D1 = Eigen::MatrixXd(o.d1);
  const Eigen::MatrixXd S1D0 = P.asDiagonal() * D0;
  return D1.transpose() * o.g.star2.asDiagonal() * D1 + S1D0 * o.g.star0.cwiseInverse().asDiagonal() * S1D0.transpose();
}

// Eigenvectors of the kernel (eigenvalues below 1e-9 of the largest).
Eigen::MatrixXd laplacianKernel(const Operators& o, const Eigen::VectorXd& P) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(denseLaplacian(o, P));
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  int k = 0;
  while (k < lambda.size() && lambda[k] < 1e-9 * lambda[lambda.size() - 1]) ++k;
  return eig.eigenvectors().leftCols(k);
}

// The dimension of the span of the harmonic parts of `count` random 1-forms (singular values above 1e-6 of
// the largest, relative to the forms' size).
int harmonicRank(const Operators& o, int count) {
  Eigen::MatrixXd H(o.t.numEdges, count);
  double typical = 0;
  for (int k = 0; k < count; ++k) {
    const Eigen::VectorXd c = randomOneForm(o.t.numEdges, 100 + k);
    H.col(k) = o.decompose(c).harmonic;
    typical = std::max(typical, c.norm());
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(H);
  int rank = 0;
  for (int k = 0; k < svd.singularValues().size(); ++k) rank += svd.singularValues()[k] > 1e-6 * typical;
  return rank;
}

// Line integral of a 1-form along a closed vertex loop (canonical edge orientation: lower index first).
double circulation(const MeshTopology& t, const Eigen::VectorXd& c, const std::vector<int>& loop) {
  double sum = 0;
  for (size_t k = 0; k < loop.size(); ++k) {
    const int a = loop[k], b = loop[(k + 1) % loop.size()];
    const int e = findEdge(t, a, b);
    EXPECT_GE(e, 0);
    sum += a < b ? c[e] : -c[e];
  }
  return sum;
}

// A stroke around the tube of torus(n, m, ...): the centroids of the strip of faces between vertex rings 0
// and 1, in the direction of increasing u, closed.
std::vector<SurfacePoint> strokeAroundTheHole(int n) {
  std::vector<SurfacePoint> points;
  for (int i = 0; i <= n; ++i) points.push_back({2 * (i % n), {1.0 / 3, 1.0 / 3, 1.0 / 3}});
  return points;
}

// A stroke along an arc of latitude on a sphere-like mesh.
std::vector<SurfacePoint> latitudeStroke(const SurfaceMesh& m, double z, double from, double to, int samples) {
  std::vector<SurfacePoint> points;
  const double r = std::sqrt(1 - z * z);
  for (int k = 0; k <= samples; ++k) {
    const double a = from + (to - from) * k / samples;
    points.push_back(surfacePointNear(m, {r * std::cos(a), r * std::sin(a), z}));
  }
  return points;
}

int nearestVertex(const SurfaceMesh& m, const Eigen::Vector3d& x) {
  int best = 0;
  double bestDistance = 1e300;
  for (int v = 0; v < m.numVertices(); ++v) {
    const double d = (Eigen::Vector3d(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]) - x).norm();
    if (d < bestDistance) bestDistance = d, best = v;
  }
  return best;
}

}  // namespace

TEST(Hodge, AnyOneFormSplitsIntoOrthogonalCurlFreeDivergenceFreeAndHarmonicParts) {
  const std::vector<std::pair<std::string, SurfaceMesh>> meshes = {
      {"sphere", icosphere(3)},
      {"torus", torus(24, 12, 2, 0.7)},
      {"genus-2 plate", holedPlate(5, 3, {{1, 1}, {3, 1}}, 2)},
      {"annulus", flatAnnulus(5, 32, 0.5, 1.0)},
      {"two components", disjointUnion(icosphere(2), torus(12, 8, 2, 0.7))}};
  for (const auto& [name, m] : meshes) {
    const Operators o(m);
    expectDecomposition(o, randomOneForm(o.t.numEdges, 7), name + ", random 1-form");
    Designer d(m);
    d.addSource(0, 1.0);
    d.addVortex(m.numFaces() / 2, 1.0);
    const double u[3] = {0.3, 0, 1};
    d.addVector(m.numFaces() / 3, u, 10.0);
    d.solve();
    expectDecomposition(o, asVector(d.oneForm()), name + ", designed field");
    // The Designer's read-out is the same decomposition of its own field.
    const HodgeDecomposition viaDesigner = d.hodgeDecomposition();
    const HodgeDecomposition direct = o.decompose(asVector(d.oneForm()));
    EXPECT_LE((viaDesigner.harmonic - direct.harmonic).norm(), 1e-14 * asVector(d.oneForm()).norm());
  }
}

TEST(Hodge, HarmonicSpaceHasTheDimensionOfTheFirstCohomology) {
  // Kernel of the 1-form Laplacian, assembled here: 2g on a closed surface.
  const Operators sphere(icosphere(2)), torus1(torus(16, 10, 2, 0.7));
  EXPECT_EQ(laplacianKernel(sphere, sphere.g.star1).cols(), 0);
  EXPECT_EQ(laplacianKernel(torus1, torus1.g.star1).cols(), 2);
  EXPECT_EQ(laplacianKernel(torus1, torus1.g.whitneyMass1).cols(), 2);
  // The span of the decomposition's harmonic parts of random 1-forms.
  EXPECT_EQ(harmonicRank(Operators(icosphere(2)), 6), 0);
  EXPECT_EQ(harmonicRank(Operators(torus(16, 10, 2, 0.7)), 6), 2);
  EXPECT_EQ(harmonicRank(Operators(holedPlate(5, 3, {{1, 1}, {3, 1}}, 2)), 8), 4);  // genus 2
  EXPECT_EQ(harmonicRank(Operators(flatAnnulus(4, 24, 0.5, 1.0)), 4), 1);          // one boundary loop more
  // And the harmonic part is the orthogonal projection onto that kernel, in the decomposition's inner product
  // (this torus has edges with *1 <= 0, so it is the Whitney mass; the kernel is that of the Laplacian with it).
  const Operators& o = torus1;
  const Eigen::VectorXd c = randomOneForm(o.t.numEdges, 3);
  const HodgeDecomposition h = o.decompose(c);
  const Eigen::MatrixXd K = laplacianKernel(o, h.metric);
  ASSERT_EQ(K.cols(), 2);
  const Eigen::MatrixXd PK = h.metric.asDiagonal() * K;
  const Eigen::VectorXd projection = K * (K.transpose() * PK).ldlt().solve(PK.transpose() * c);
  EXPECT_GT(projection.norm(), 0.01 * c.norm());
  EXPECT_LE((h.harmonic - projection).norm(), 1e-8 * projection.norm());
}

TEST(Hodge, SphereFieldsHaveNoHarmonicPart) {
  const SurfaceMesh m = icosphere(4);
  Designer d(m);
  d.addSource(nearestVertex(m, {0, 0, 1}), 1.0);
  d.addSink(nearestVertex(m, {0, 0, -1}), 1.0);
  d.addVortex(surfacePointNear(m, {1, 0, 0}).face, 0.8);
  d.addStroke(latitudeStroke(m, 0.3, 0.2, 1.4, 24), 1.0, 10.0);
  d.solve();
  const HodgeDecomposition h = d.hodgeDecomposition();
  const Eigen::VectorXd c = asVector(d.oneForm());
  EXPECT_LE(std::sqrt(inner(h, h.harmonic, h.harmonic) / inner(h, c, c)), 1e-10);
  EXPECT_GT(inner(h, h.exact, h.exact), 0.01 * inner(h, c, c));
  EXPECT_GT(inner(h, h.coexact, h.coexact), 0.01 * inner(h, c, c));
}

TEST(Hodge, SourcesAndSinksAreCurlFreeAndVorticesDivergenceFree) {
  const SurfaceMesh m = icosphere(4);
  const auto relative = [](const HodgeDecomposition& h, const Eigen::VectorXd& part, const Eigen::VectorXd& c) {
    return std::sqrt(inner(h, part, part) / inner(h, c, c));
  };
  {
    Designer d(m);
    d.addSource(nearestVertex(m, {0.3, 0.2, 1}), 1.0);
    d.addSink(nearestVertex(m, {-0.5, 0.1, -1}), 1.0);
    d.solve();
    const HodgeDecomposition h = d.hodgeDecomposition();
    ASSERT_EQ(h.metricName, "star1");  // the designer's divergence uses *1
    const Eigen::VectorXd c = asVector(d.oneForm());
    EXPECT_LE(relative(h, h.coexact, c), 1e-8);
    EXPECT_LE(relative(h, h.harmonic, c), 1e-8);
    EXPECT_NEAR(relative(h, h.exact, c), 1.0, 1e-8);
  }
  {
    Designer d(m);
    d.addVortex(surfacePointNear(m, {1, 0.2, 0.1}).face, 1.0);
    d.addVortex(surfacePointNear(m, {-0.3, -1, 0.4}).face, -1.0);
    d.solve();
    const HodgeDecomposition h = d.hodgeDecomposition();
    const Eigen::VectorXd c = asVector(d.oneForm());
    EXPECT_LE(relative(h, h.exact, c), 1e-8);
    EXPECT_LE(relative(h, h.harmonic, c), 1e-8);
    EXPECT_NEAR(relative(h, h.coexact, c), 1.0, 1e-8);
  }
}

// A stroke around the hole of a torus asks for circulation no exact or coexact field on a sphere could give:
// the harmonic part carries it. What is checked: (1) the exact part's circulation around every closed loop
// is 0 (telescoping potential differences), so the closed part exact + harmonic has the harmonic part's
// circulation; (2) the harmonic part's circulation is the same around every loop of one homology class (the
// rings j = const, and separately the rings i = const), since d1 h = 0 (Stokes); (3) it is nonzero around
// the hole. The whole field's circulation is NOT the harmonic one in general: the coexact part's line
// integral around a closed loop equals the vorticity it encloses on one side and varies from ring to ring
// (a vortex is added for a coexact part: the stroke alone is met almost exactly by a harmonic field).
TEST(Hodge, HarmonicPartOfAStrokeAroundTheHoleCarriesItsCirculation) {
  const int n = 32, mm = 16;
  const SurfaceMesh m = torus(n, mm, 2, 0.7);
  Designer d(m);
  d.addStroke(strokeAroundTheHole(n), 1.0, 10.0);
  d.addVortex(2 * ((mm / 2) * n + 5), 3.0);
  d.solve();
  const HodgeDecomposition h = d.hodgeDecomposition();
  const MeshTopology& t = d.topology();
  const Eigen::VectorXd c = asVector(d.oneForm());
  const auto ring = [&](int j) {  // around the hole (u direction)
    std::vector<int> loop;
    for (int i = 0; i < n; ++i) loop.push_back(j * n + i);
    return loop;
  };
  const auto meridian = [&](int i) {  // around the tube (v direction)
    std::vector<int> loop;
    for (int j = 0; j < mm; ++j) loop.push_back(j * n + i);
    return loop;
  };
  double scale = 0;  // sum |c_e| along ring 0: the size of a line integral's terms
  for (int i = 0; i < n; ++i) scale += std::abs(c[findEdge(t, i, (i + 1) % n)]);
  const double around = circulation(t, h.harmonic, ring(0));
  EXPECT_GT(std::abs(around), 0.1 * scale);
  std::vector<double> whole;
  for (int j = 0; j < mm; ++j) {
    EXPECT_LE(std::abs(circulation(t, h.exact, ring(j))), 1e-12 * scale) << "ring " << j;
    EXPECT_NEAR(circulation(t, h.exact + h.harmonic, ring(j)), around, 1e-8 * scale) << "ring " << j;
    EXPECT_NEAR(circulation(t, h.harmonic, ring(j)), around, 1e-8 * scale) << "ring " << j;
    whole.push_back(circulation(t, c, ring(j)));
  }
  const double tube = circulation(t, h.harmonic, meridian(0));
  for (int i = 0; i < n; ++i) {
    EXPECT_LE(std::abs(circulation(t, h.exact, meridian(i))), 1e-12 * scale);
    EXPECT_NEAR(circulation(t, h.harmonic, meridian(i)), tube, 1e-8 * scale) << "meridian " << i;
  }
  // The whole field's circulation varies from ring to ring (its coexact part) around the harmonic one.
  const auto [lo, hi] = std::minmax_element(whole.begin(), whole.end());
  EXPECT_GT(*hi - *lo, 1e-6 * scale);
  const HodgeEnergyShares s = hodgeEnergyShares(h);
  EXPECT_GT(s.harmonic, 0.1);
  std::cout << "torus stroke: harmonic circulation around the hole " << around << ", around the tube " << tube
            << "; whole field around the hole from " << *lo << " to " << *hi << "; shares exact " << s.exact
            << " coexact " << s.coexact << " harmonic " << s.harmonic << "\n";
}

// Timings and energy shares for the report: run with --gtest_also_run_disabled_tests.
TEST(Hodge, DISABLED_TimingAndShares) {
  for (const int level : {3, 5, 6}) {
    const SurfaceMesh m = icosphere(level);
    Designer d(m);
    d.addSource(nearestVertex(m, {0, 0, 1}), 1.0);
    d.addSink(nearestVertex(m, {0, 0, -1}), 1.0);
    d.addStroke(latitudeStroke(m, 0.3, 0.2, 1.4, 24), 1.0, 10.0);
    d.solve();
    double best = 1e300;
    HodgeDecomposition h;
    for (int k = 0; k < 3; ++k) {
      h = d.hodgeDecomposition();
      best = std::min(best, h.milliseconds);
    }
    const HodgeEnergyShares s = hodgeEnergyShares(h);
    const Eigen::VectorXd c = asVector(d.oneForm());
    const SparseMatrix d0 = exteriorDerivative0(d.topology()), d1 = exteriorDerivative1(d.topology());
    const double n2 = inner(h, c, c);
    std::cout << "  orthogonality |<exact,coexact>|, |<exact,harmonic>|, |<coexact,harmonic>| / |c|^2: "
              << std::abs(inner(h, h.exact, h.coexact)) / n2 << ", " << std::abs(inner(h, h.exact, h.harmonic)) / n2
              << ", " << std::abs(inner(h, h.coexact, h.harmonic)) / n2 << "; divergence of coexact (relative) "
              << (d0.transpose() * (h.metric.asDiagonal() * h.coexact)).norm() /
                     (d0.transpose() * (h.metric.asDiagonal() * c)).norm()
              << "; curl of harmonic (relative) " << (d1 * h.harmonic).norm() / (d1 * c).norm() << "\n";
    std::cout << "icosphere(" << level << ") E=" << d.topology().numEdges << ": decomposition " << best
              << " ms (best of 3); source+sink+stroke shares exact " << s.exact << " coexact " << s.coexact
              << " harmonic " << s.harmonic << " (design solve " << d.stats().factorMs + d.stats().solveMs
              << " ms)\n";
  }
  {
    const SurfaceMesh m = torus(64, 32, 2, 0.7);
    Designer d(m);
    d.addStroke(strokeAroundTheHole(64), 1.0, 10.0);
    d.solve();
    const HodgeDecomposition h = d.hodgeDecomposition();
    const HodgeEnergyShares s = hodgeEnergyShares(h);
    std::cout << "torus(64,32) E=" << d.topology().numEdges << ": decomposition " << h.milliseconds
              << " ms; stroke shares exact " << s.exact << " coexact " << s.coexact << " harmonic "
              << s.harmonic << "\n";
  }
  {
    const SurfaceMesh m = holedPlate(7, 3, {{1, 1}, {3, 1}, {5, 1}}, 4);
    Designer d(m);
    d.addSource(0, 1.0);
    d.addVortex(m.numFaces() / 2, 1.0);
    const double u[3] = {1, 0, 0};
    d.addVector(m.numFaces() / 3, u, 10.0);
    d.solve();
    const HodgeDecomposition h = d.hodgeDecomposition();
    const HodgeEnergyShares s = hodgeEnergyShares(h);
    std::cout << "genus-3 plate E=" << d.topology().numEdges << " metric " << h.metricName << ": decomposition "
              << h.milliseconds << " ms; source+vortex+vector shares exact " << s.exact << " coexact "
              << s.coexact << " harmonic " << s.harmonic << "\n";
  }
}

// ---- the command line -------------------------------------------------------------------------------------

#ifdef TVF_CLI_PATH
namespace {

namespace fs = std::filesystem;

fs::path tempPath(const std::string& name) {
  return fs::temp_directory_path() / ("hodge_" + std::to_string(getpid()) + "_" + name);
}

fs::path writeOff(const std::string& name, const SurfaceMesh& m) {
  const fs::path path = tempPath(name);
  std::ofstream out(path);
  out << "OFF\n" << m.numVertices() << " " << m.numFaces() << " 0\n";
  out.precision(17);
  for (int v = 0; v < m.numVertices(); ++v)
    out << m.positions[3 * v] << " " << m.positions[3 * v + 1] << " " << m.positions[3 * v + 2] << "\n";
  for (int f = 0; f < m.numFaces(); ++f)
    out << "3 " << m.triangles[3 * f] << " " << m.triangles[3 * f + 1] << " " << m.triangles[3 * f + 2] << "\n";
  return path;
}

fs::path writeText(const std::string& name, const std::string& text) {
  const fs::path path = tempPath(name);
  std::ofstream(path) << text;
  return path;
}

// 8-bit RGBA samples, read by libpng.
std::vector<uint8_t> decodePng(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  EXPECT_TRUE(png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) << path;
  image.format = PNG_FORMAT_RGBA;
  std::vector<uint8_t> out(PNG_IMAGE_SIZE(image));
  EXPECT_TRUE(png_image_finish_read(&image, nullptr, out.data(), 0, nullptr)) << path;
  return out;
}

int largestDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  EXPECT_EQ(a.size(), b.size());
  int most = 0;
  for (size_t k = 0; k < std::min(a.size(), b.size()); ++k) most = std::max(most, std::abs(int(a[k]) - int(b[k])));
  return most;
}

std::string strokeJson(const std::vector<SurfacePoint>& points) {
  nlohmann::json list = nlohmann::json::array();
  for (const SurfacePoint& p : points) list.push_back({{"face", p.face}, {"bary", {p.bary[0], p.bary[1], p.bary[2]}}});
  return nlohmann::json{{"type", "stroke"}, {"points", list}, {"strength", 1.0}, {"weight", 10.0}}.dump();
}

}  // namespace

TEST(Cli, DesignHodgeWritesThePartsAndTheirEnergyShares) {
  const SurfaceMesh m = icosphere(3);
  const fs::path mesh = writeOff("sphere.off", m);
  const fs::path design = writeText(
      "mixed.json", R"({"boundary": "free", "gamma": 0, "constraints": [
      {"type": "source", "vertex": 0, "strength": 1}, {"type": "sink", "vertex": 3, "strength": 1},
      {"type": "vortex", "face": 100, "strength": 1}, )" +
                        strokeJson(latitudeStroke(m, 0.3, 0.2, 1.4, 16)) + "]}");
  const fs::path out = tempPath("field.json");
  const CliRun r = runTvf("design " + mesh.string() + " " + design.string() + " -o " + out.string() + " --hodge");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(out);
  const auto field = nlohmann::json::parse(in);
  ASSERT_TRUE(field.contains("hodge"));
  const auto& hodge = field["hodge"];
  const std::vector<double> c = field["oneForm"];
  for (const char* key : {"exact", "coexact", "harmonic"}) ASSERT_EQ(hodge[key].size(), c.size()) << key;
  EXPECT_EQ(hodge["potential0"].size(), static_cast<size_t>(m.numVertices()));
  EXPECT_EQ(hodge["potential2"].size(), static_cast<size_t>(m.numFaces()));
  const auto part = [&](const char* key) { return asVector(hodge[key].get<std::vector<double>>()); };
  const Eigen::VectorXd exact = part("exact"), coexact = part("coexact"), harmonic = part("harmonic");
  EXPECT_LE((exact + coexact + harmonic - asVector(c)).norm(), 1e-10 * asVector(c).norm());
  const double se = hodge["energyShares"]["exact"], sc = hodge["energyShares"]["coexact"],
               sh = hodge["energyShares"]["harmonic"];
  EXPECT_NEAR(se + sc + sh, 1.0, 1e-10);
  EXPECT_GT(se, 0.01);
  EXPECT_GT(sc, 0.01);
  EXPECT_LT(sh, 1e-16);  // a sphere: |h| / |c| < 1e-8
  EXPECT_EQ(hodge["metric"], "star1");
  // The shares are those of the library's decomposition of the same field.
  Designer d(m);
  applyDesignDocument(d, nlohmann::json::parse(std::ifstream(design)));
  d.solve();
  const HodgeEnergyShares s = hodgeEnergyShares(d.hodgeDecomposition());
  EXPECT_NEAR(se, s.exact, 1e-9);
  EXPECT_NEAR(sc, s.coexact, 1e-9);
  // Without --hodge there is none.
  const CliRun plain = runTvf("design " + mesh.string() + " " + design.string());
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("hodge"));
  fs::remove(out);
}

TEST(Cli, ExportComponentExportsThatPartOfTheField) {
  const SurfaceMesh m = icosphere(3);
  const fs::path mesh = writeOff("sphere.off", m);
  const std::string sourceSink =
      R"({"type": "source", "vertex": 0, "strength": 1}, {"type": "sink", "vertex": 3, "strength": 1})";
  const fs::path mixed = writeText("mixed.json", R"({"boundary": "free", "gamma": 0, "constraints": [)" + sourceSink +
                                                     R"(, {"type": "vortex", "face": 100, "strength": 2}]})");
  const fs::path pure = writeText("pure.json", R"({"boundary": "free", "gamma": 0, "constraints": [)" + sourceSink + "]}");
  const auto flowMap = [&](const fs::path& design, const std::string& component) {
    const fs::path png = tempPath(component + "_" + design.stem().string() + ".png");
    const CliRun r = runTvf("export " + mesh.string() + " " + design.string() + " --flowmap " + png.string() +
                            " --size 128" + (component.empty() ? "" : " --component " + component));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const std::vector<uint8_t> pixels = decodePng(png);
    fs::remove(png);
    return pixels;
  };
  const std::vector<uint8_t> whole = flowMap(mixed, "whole"), plain = flowMap(mixed, ""),
                             exact = flowMap(mixed, "exact"), coexact = flowMap(mixed, "coexact"),
                             pureWhole = flowMap(pure, "whole"), pureExact = flowMap(pure, "exact");
  EXPECT_EQ(largestDifference(whole, plain), 0);  // whole is the default
  EXPECT_GT(largestDifference(exact, whole), 20);
  EXPECT_GT(largestDifference(coexact, whole), 20);
  EXPECT_GT(largestDifference(exact, coexact), 20);
  // The mixed design's exact part is the pure source + sink field (the vortex adds only a coexact part; the
  // source and sink are the same), and a pure source + sink design is its own exact part. Quantization to 8
  // bits may round a sample the other way where two fields differ by round-off.
  EXPECT_LE(largestDifference(pureExact, pureWhole), 1);
  EXPECT_LE(largestDifference(exact, pureWhole), 1);
  // The GLB takes the option too; a bad component is refused with the choices.
  const fs::path glb = tempPath("part.glb");
  EXPECT_EQ(runTvf("export " + mesh.string() + " " + mixed.string() + " --glb " + glb.string() +
                   " --size 64 --component harmonic")
                .exitCode,
            0);
  EXPECT_GT(fs::file_size(glb), 0u);
  fs::remove(glb);
  const CliRun bad = runTvf("export " + mesh.string() + " " + mixed.string() + " --flowmap " +
                            tempPath("x.png").string() + " --component gradient");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("exact"), std::string::npos) << bad.err;
}
#endif
