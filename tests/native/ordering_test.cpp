// The fill-reducing ordering: METIS nested dissection and AMD must give the same field, and the ordering is
// computed once and reused while boundary-condition and gamma changes keep the matrix's sparsity pattern.
#include <gtest/gtest.h>

#include <cmath>

#include "design/designer.h"
#include "test_meshes.h"

namespace tvf {
namespace {

using testing::flatGrid;
using testing::icosphere;

double relativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, n = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    d += (a[k] - b[k]) * (a[k] - b[k]);
    n += b[k] * b[k];
  }
  return std::sqrt(d / n);
}

// A stroke through the barycentres of a few faces, a source and a vortex: every kind of right-hand side, and
// rank-k updates of the factor.
void design(Designer& d) {
  const int32_t nF = d.mesh().numFaces();
  std::vector<SurfacePoint> points;
  for (int32_t f : {nF / 7, nF / 7 + 1, nF / 7 + 2}) points.push_back({f, {0.2, 0.3, 0.5}});
  d.addStroke(points, 1.0, 1.0);
  d.addSource(d.mesh().triangles[0], 1.0);
  d.addVortex(nF / 2, -0.5);
  d.solve();
}

// Both meshes have more edges than the subgraph size at which the nested dissection stops (20000), so the
// METIS build really partitions: its factor has a different fill than AMD's.
TEST(Ordering, MetisAndAmdGiveTheSameFieldOnAClosedSurface) {
  const SurfaceMesh m = icosphere(5);  // 30720 edges
  Designer metis(m), amd(m);
  amd.setMetisOrdering(false);
  design(metis);
  design(amd);
  EXPECT_NE(metis.stats().factorKind.find("METIS"), std::string::npos) << metis.stats().factorKind;
  EXPECT_NE(amd.stats().factorKind.find("AMD"), std::string::npos) << amd.stats().factorKind;
  EXPECT_NE(metis.stats().nnzPerRowL, amd.stats().nnzPerRowL);
  EXPECT_LT(relativeDifference(metis.oneForm(), amd.oneForm()), 1e-9);
}

TEST(Ordering, MetisAndAmdGiveTheSameFieldWithFreeAndNormalBoundaries) {
  const SurfaceMesh m = flatGrid(92, 1.0, true);  // 25576 edges
  Designer metis(m), amd(m);
  amd.setMetisOrdering(false);
  design(metis);
  design(amd);
  EXPECT_NE(metis.stats().nnzPerRowL, amd.stats().nnzPerRowL);
  EXPECT_LT(relativeDifference(metis.oneForm(), amd.oneForm()), 1e-9);  // 1.1e-10 measured
  for (Designer* d : {&metis, &amd}) {
    d->setBoundary(BoundaryCondition::normal());
    d->solve();
  }
  EXPECT_LT(relativeDifference(metis.oneForm(), amd.oneForm()), 1e-9);  // 5e-15 measured
}

TEST(Ordering, MetisAndAmdAgreeToTheConditioningOfTangentialAndBiLaplacianSystems) {
  // On this square the tangential boundary leaves a near-kernel (a field circulating along the boundary that
  // only the constraints pin down), and gamma > 0 squares the Laplacian's condition number: two correct
  // factorizations differ by round-off times that (measured 1.7e-8 and 3.4e-8), not by 1e-9.
  const SurfaceMesh m = flatGrid(92, 1.0, true);
  Designer metis(m), amd(m);
  amd.setMetisOrdering(false);
  for (Designer* d : {&metis, &amd}) {
    d->setBoundary(BoundaryCondition::tangential());
    design(*d);
  }
  EXPECT_LT(relativeDifference(metis.oneForm(), amd.oneForm()), 1e-6);
  for (Designer* d : {&metis, &amd}) {
    d->setGamma(0.01);
    d->solve();
  }
  EXPECT_LT(relativeDifference(metis.oneForm(), amd.oneForm()), 1e-6);
}

TEST(Ordering, ReusedAcrossBoundaryAndGammaChangesThatKeepThePattern) {
  const SurfaceMesh m = flatGrid(92, 1.0, true);
  Designer d(m);
  d.setBoundary(BoundaryCondition::tangential());
  d.factor();
  EXPECT_FALSE(d.stats().analysisReused);
  design(d);
  // Another fixed angle: the same boundary rows with other coefficients.
  d.setBoundary(BoundaryCondition::fixedAngle(0.3));
  d.solve();
  EXPECT_TRUE(d.stats().analysisReused);
  // gamma > 0 widens the stencil (a new pattern); another gamma > 0 keeps it.
  d.setGamma(0.01);
  d.solve();
  EXPECT_FALSE(d.stats().analysisReused);
  d.setGamma(0.02);
  d.solve();
  EXPECT_TRUE(d.stats().analysisReused);
  // The reused ordering gives what a fresh designer computes for the same settings and constraints.
  Designer fresh(m);
  fresh.setBoundary(BoundaryCondition::fixedAngle(0.3));
  fresh.setGamma(0.02);
  design(fresh);
  EXPECT_FALSE(fresh.stats().analysisReused);
  EXPECT_LT(relativeDifference(d.oneForm(), fresh.oneForm()), 1e-9);
  // Free boundary: the divergence rows change shape, so the pattern does, and the ordering is recomputed.
  d.setBoundary(BoundaryCondition::makeFree());
  d.solve();
  EXPECT_FALSE(d.stats().analysisReused);
}

TEST(Ordering, ReusedOnAClosedSurfaceWhoseBoundaryConditionCannotMatter) {
  Designer d(icosphere(3));
  d.solve();
  EXPECT_FALSE(d.stats().analysisReused);
  d.setBoundary(BoundaryCondition::tangential());  // no boundary edges: the same matrix
  d.solve();
  EXPECT_TRUE(d.stats().analysisReused);
}

}  // namespace
}  // namespace tvf
