// Stripes fitted to the surface's loops (StripeOptions::fitLoops, direction/stripe_loop_fit.h) against
// analytic truth. On a torus of revolution (radii R and r, rho = R + r cos(theta) from its axis) a field at a
// constant angle beta to its parallels has, with the spacing growing as rho (e^u = R / rho, which the adapted
// spacing finds: it makes the turned field closed and keeps the frequency's area mean f), a phase whose
// stripes follow it exactly only where its periods round both loops are whole: 2 pi f R sin(beta) stripes
// cross a parallel and f R cos(beta) 2 pi r / sqrt(R^2 - r^2) a meridian. At the angle where the second is
// 0.3 of the first, f puts 20.6 and 6.2 there, and the eigenvector rounds each (21 and 6: a ratio the field
// does not have, so its stripes cross the field); neither loop is open, so no turn of the phase can make up
// the fractions. Fitted, the pattern takes 20 and 6 at 0.99 f.
#include "direction/stripe_loop_fit.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <complex>

#include "direction/stripe_pattern.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "stripe_test_fields.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

constexpr double kR = 2.0, kr = 0.7;
constexpr int kAround = 96, kTube = 48;  // torus(kAround, kTube, ...): vertex (i, j) is j kAround + i

// cot(beta) r / sqrt(R^2 - r^2) = 0.3: a meridian crosses 0.3 as many stripes as a parallel.
double beta() {
  return std::atan(kr / (0.3 * std::sqrt(kR * kR - kr * kr)));
}

std::vector<double> helicalField(const SurfaceMesh& m) {
  std::vector<double> out;
  for (int32_t v = 0; v < m.numVertices(); ++v) {
    const Eigen::Vector3d p = vertexPosition(m, v);
    const Eigen::Vector3d parallel = Eigen::Vector3d(-p.y(), p.x(), 0).normalized();
    const Eigen::Vector3d centre = kR * Eigen::Vector3d(p.x(), p.y(), 0).normalized();
    const Eigen::Vector3d meridian = parallel.cross((p - centre).normalized());
    const Eigen::Vector3d d = std::cos(beta()) * parallel + std::sin(beta()) * meridian;
    out.insert(out.end(), {d.x(), d.y(), d.z()});
  }
  return out;
}

// The stripes' area-mean angle to the field, degrees.
double degreesOffTheField(const SurfaceMesh& m, const StripePattern& p, const std::vector<double>& field) {
  double sum = 0, area = 0;
  for (int32_t f = 0; f < m.numFaces(); ++f) {
    const FaceAngle a = angleOffTheField(m, p, field, f);
    sum += a.area * a.angle, area += a.area;
  }
  return sum / area * 180 / M_PI;
}

// psi's winding along the closed loop of vertices `at(k)`, k < count: the stripes crossing it.
template <class At>
double stripesAlong(const StripePattern& p, int count, At at) {
  double turn = 0;
  for (int k = 0; k < count; ++k) {
    const int32_t a = at(k), b = at((k + 1) % count);
    turn += std::arg(std::complex<double>(p.psi[2 * b], p.psi[2 * b + 1]) *
                     std::conj(std::complex<double>(p.psi[2 * a], p.psi[2 * a + 1])));
  }
  return std::abs(turn) / (2 * M_PI);
}

}  // namespace

TEST(StripeLoopFit, ATorusTakesTheNearestWholeNumbersOfHelicalStripes) {
  const SurfaceMesh m = torus(kAround, kTube, kR, kr);
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  ASSERT_TRUE(stripe::hasLoops(t));
  const std::vector<double> field = helicalField(m);
  StripeOptions o;
  o.symmetry = 2;
  o.adaptSpacing = true;
  o.frequency = 20 / (2 * M_PI * kR * std::sin(beta()) * 0.97);  // 20 and 6 at 0.97 f
  o.fitLoops = false;
  const StripePattern asked = stripePattern(m, t, g, field, o);
  o.fitLoops = true;
  const StripePattern fitted = stripePattern(m, t, g, field, o);
  const auto parallel = [](const StripePattern& p) {
    return stripesAlong(p, kAround, [](int i) { return i; });
  };
  const auto meridian = [](const StripePattern& p) {
    return stripesAlong(p, kTube, [](int j) { return j * kAround; });
  };
  std::cout << "[ measured ] asked: " << degreesOffTheField(m, asked, field) << " deg off, "
            << parallel(asked) << " / " << meridian(asked) << " stripes; fitted x" << fitted.loopFit << ": "
            << degreesOffTheField(m, fitted, field) << " deg off, " << parallel(fitted) << " / "
            << meridian(fitted) << " stripes, " << fitted.fitMs << " ms\n";
  EXPECT_DOUBLE_EQ(asked.loopFit, 1.0);
  EXPECT_NEAR(parallel(asked), 21.0, 1e-9);  // 20.6 and 6.2 rounded: the stripes turned
  EXPECT_NEAR(meridian(asked), 6.0, 1e-9);
  EXPECT_NEAR(fitted.loopFit, 0.99, 1e-12);  // the nearest factor to 1 that takes 20 and 6
  EXPECT_NEAR(parallel(fitted), 20.0, 1e-9);
  EXPECT_NEAR(meridian(fitted), 6.0, 1e-9);
  // measured 1.38 -> 0.73 degrees (what is left: the adapted spacing's own error, the same at every factor
  // that takes 20 and 6)
  EXPECT_LT(degreesOffTheField(m, fitted, field), 0.6 * degreesOffTheField(m, asked, field));
}

// A surface without loops keeps the asked frequency, an edit's pattern keeps the factor the pattern before it
// found (fitted once for a frequency and symmetry), and a grid keeps the asked one.
TEST(StripeLoopFit, OnlyALoopedSurfaceIsFittedAndOnlyOnceAFrequency) {
  {
    const SurfaceMesh m = flatGrid(12, 1.0, true);
    const MeshTopology t = buildTopology(m);
    EXPECT_FALSE(stripe::hasLoops(t));
    StripeOptions o;
    o.symmetry = 2;
    o.adaptSpacing = true;
    o.frequency = 3;
    const StripePattern p = stripePattern(m, t, computeMeshGeometry(m, t), constantField(m, {1, 0, 0}), o);
    EXPECT_DOUBLE_EQ(p.loopFit, 1.0);
    EXPECT_EQ(p.fitMs, 0.0);
  }
  const SurfaceMesh m = torus(kAround, kTube, kR, kr);
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  std::vector<double> field = helicalField(m);
  StripeOptions o;
  o.symmetry = 2;
  o.adaptSpacing = true;
  o.frequency = 20 / (2 * M_PI * kR * std::sin(beta()) * 0.97);
  StripeWorkspace w;
  const StripePattern first = stripePattern(m, t, g, field, o, &w);
  EXPECT_GT(first.fitMs, 0.0);
  // An edit: the field turned by 3 degrees round the first vertices' normals (a whole pattern again).
  const std::vector<double> normals = vertexNormals(m);
  for (int32_t v = 0; v < 200; ++v) {
    Eigen::Map<Eigen::Vector3d> d(&field[3 * v]);
    d = Eigen::AngleAxisd(3 * M_PI / 180, Eigen::Vector3d(&normals[3 * v])) * Eigen::Vector3d(d);
  }
  const StripePattern edited = stripePattern(m, t, g, field, o, &w);
  EXPECT_DOUBLE_EQ(edited.loopFit, first.loopFit);
  EXPECT_EQ(edited.fitMs, 0.0);
  // Another frequency is fitted again.
  o.frequency *= 1.5;
  const StripePattern other = stripePattern(m, t, g, field, o, &w);
  EXPECT_GT(other.fitMs, 0.0);
  // A grid is not (StripeOptions::fitLoops).
  o.symmetry = 4;
  const StripePattern grid = stripePattern(m, t, g, field, o);
  EXPECT_DOUBLE_EQ(grid.loopFit, 1.0);
  EXPECT_EQ(grid.fitMs, 0.0);
}
