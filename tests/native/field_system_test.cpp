// The design's field systems behind one interface (design/field_system.h): what the Designer does for a
// vector field it does for line and cross fields by the same calls. Checked against independent solves: a
// stroke's update held beside the factor of an N-direction field gives the field of the update put into the
// factor (to round-off), and is then put in by applyDeferredUpdates; a round trip through another symmetry
// resumes the system it left, its ordering reused, its field the one a fresh design solves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "design/designer.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

std::vector<SurfacePoint> centresStroke(const std::vector<int32_t>& faces) {
  std::vector<SurfacePoint> points;
  for (const int32_t f : faces) points.push_back({f, {0.2, 0.3, 0.5}});
  return points;
}

// The largest difference between two face-vector arrays relative to the largest vector, where an N-direction
// field's representatives are compared as lines (u and -u alike) for even N.
double relativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0, size = 0;
  for (size_t f = 0; 3 * f < a.size(); ++f) {
    double same = 0, flipped = 0;
    for (int k = 0; k < 3; ++k) {
      same += std::pow(a[3 * f + k] - b[3 * f + k], 2);
      flipped += std::pow(a[3 * f + k] + b[3 * f + k], 2);
      size = std::max(size, std::abs(b[3 * f + k]));
    }
    worst = std::max(worst, std::sqrt(std::min(same, flipped)));
  }
  return worst / std::max(size, 1e-300);
}

// A closed curved surface: no kernel, no symmetry that would make the field's directions ambiguous.
SurfaceMesh bumpy() {
  SurfaceMesh m = icosphere(3);
  for (size_t v = 0; 3 * v < m.positions.size(); ++v) {
    double* p = &m.positions[3 * v];
    const double r = 1 + 0.15 * std::sin(3 * p[0] + 1) * std::cos(2 * p[1]);
    for (int k = 0; k < 3; ++k) p[k] *= r;
  }
  return m;
}

}  // namespace

TEST(FieldSystem, HeldUpdateServesVectorLineAndCrossFields) {
  const SurfaceMesh m = bumpy();
  const auto first = centresStroke({10, 11, 12, 40});
  const auto second = centresStroke({200, 201, 230});
  for (const int n : {1, 2, 4}) {
    Designer held(m), direct(m);
    for (Designer* d : {&held, &direct}) {
      d->setSymmetry(n);
      d->addStroke(first, 1, 10);
      d->solve();  // factored, with the first stroke
    }
    held.setDeferredUpdates(true);
    held.addStroke(second, 1, 10);
    direct.addStroke(second, 1, 10);
    held.solve();
    direct.solve();
    EXPECT_LT(relativeDifference(held.faceVectors(), direct.faceVectors()), 1e-9) << "N = " << n;
    EXPECT_EQ(held.stats().factorizations, 1) << "N = " << n << ": the held update is no refactorization";
    held.applyDeferredUpdates();
    EXPECT_GT(held.stats().deferredUpdateMs, 0) << "N = " << n << ": an update was held and is now put in";
    held.solve();  // through the updated factor alone
    EXPECT_LT(relativeDifference(held.faceVectors(), direct.faceVectors()), 1e-9) << "N = " << n;
    EXPECT_EQ(held.stats().precisionRefactors, 0) << "N = " << n;
  }
}

TEST(FieldSystem, SymmetryRoundTripResumesTheSystemItLeft) {
  const SurfaceMesh m = bumpy();
  const auto stroke = centresStroke({10, 11, 12, 40});
  for (const int n : {1, 4}) {
    const int other = n == 1 ? 4 : 1;
    Designer d(m);
    d.setSymmetry(n);
    d.addStroke(stroke, 1, 10);
    d.solve();
    d.setSymmetry(other);
    d.addStroke(centresStroke({300, 301}), 1, 10);  // made while the first system is out of use
    d.solve();
    d.setSymmetry(n);
    d.solve();
    EXPECT_TRUE(d.stats().analysisReused) << "N = " << n << ": the ordering kept across the round trip";
    EXPECT_EQ(d.stats().factorizations, 2) << "N = " << n;
    Designer fresh(m);
    fresh.setSymmetry(n);
    fresh.addStroke(stroke, 1, 10);
    fresh.addStroke(centresStroke({300, 301}), 1, 10);
    fresh.solve();
    EXPECT_LT(relativeDifference(d.faceVectors(), fresh.faceVectors()), 1e-12) << "N = " << n;
  }
}

TEST(FieldSystem, BaseMatrixIsTheCurrentSystems) {
  // The vector field's base has one row per edge, an N-direction field's two per face.
  const SurfaceMesh m = bumpy();
  Designer d(m);
  const Eigen::Index edges = d.baseMatrix().rows();
  EXPECT_EQ(edges, d.topology().numEdges);
  d.setSymmetry(2);
  EXPECT_EQ(d.baseMatrix().rows(), 2 * d.topology().numFaces);
  EXPECT_GT(d.weightScale(), 0);
}
