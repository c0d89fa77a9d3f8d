// The constraints module: edge rows of vectors and strokes against constant fields, sources and sinks against
// singularity counts, validation, and the constraint set's bookkeeping and cached right-hand side.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "constraints/constraint_set.h"
#include "constraints/edge_rows.h"
#include "dec/boundary_condition.h"
#include "dec/one_form_laplacian.h"
#include "design/designer.h"
#include "mesh/mesh_checks.h"
#include "mesh/mesh_geometry.h"
#include "test_fields.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

TEST(Constraints, VectorConstraintsFromAConstantFieldReproduceItEverywhere) {
  SurfaceMesh m = flatGrid(10, 1.0, true);
  jitterPlanar(m, 0.02, 5);
  Designer d(m);
  const double u[3] = {0.6, 0.8, 0};
  for (const int f : {3, 77, 150}) d.addVector(f, u, 100.0);
  d.solve();
  EXPECT_LT(maxRelativeError(d, {0.6, 0.8, 0}), 1e-8);
}

TEST(Constraints, AShortStrokeSampledFromAConstantFieldReproducesItWithFreeBoundary) {
  SurfaceMesh m = flatGrid(12, 1.0, true);
  jitterPlanar(m, 0.02, 9);
  Designer d(m);
  const Eigen::Vector3d dir = Eigen::Vector3d(1, 0.3, 0).normalized();
  const auto stroke = straightStroke(m, {0.4, 0.45, 0}, Eigen::Vector3d(0.4, 0.45, 0) + 0.2 * dir, 12);
  d.addStroke(stroke, 2.0, 100.0);
  d.solve();
  EXPECT_LT(maxRelativeError(d, 2.0 * dir), 1e-8);
}

TEST(Constraints, StrokeDeviationShrinksMonotonicallyWithWeight) {
  const SurfaceMesh m = icosphere(3);
  Designer d(m);
  d.addSource(0, 1.0);
  d.addSink(3, 1.0);
  // A stroke along a circle of latitude, across the source-to-sink flow, so the two compete.
  std::vector<SurfacePoint> stroke;
  for (int s = 0; s <= 20; ++s) {
    const double a = 0.05 * s;
    stroke.push_back(surfacePointNear(m, Eigen::Vector3d(std::cos(a), std::sin(a), 0.2).normalized()));
  }
  const int id = d.addStroke(stroke, 1.0, 1e-2);
  const std::vector<EdgeRow> rows = strokeRows(m, buildTopology(m), stroke);
  ASSERT_GT(rows.size(), 10u);
  double previous = INFINITY;
  for (const double w : {1e-2, 1e-1, 1.0, 10.0, 100.0, 1e4}) {
    d.setWeight(id, w);
    d.solve();
    double deviation = 0, size = 0;
    for (const auto& r : rows) {
      deviation = std::max(deviation, std::abs(d.oneForm()[r.edge] - r.value));
      size = std::max(size, std::abs(r.value));
    }
    EXPECT_LT(deviation, previous) << "weight " << w;
    previous = deviation;
    if (w == 1e4) EXPECT_LT(deviation / size, 1e-2);
  }
}

TEST(Constraints, SourceSinkPairOnASphereGivesExactlyTwoSingularities) {
  Designer d(icosphere(3));
  d.addSource(0, 1.0);
  d.addSink(3, 1.0);
  d.solve();
  ASSERT_EQ(d.singularities().size(), 2u);
  int sum = 0;
  for (const auto& s : d.singularities()) {
    EXPECT_TRUE(s.vertex == 0 || s.vertex == 3) << s.vertex;
    EXPECT_EQ(s.index, 1.0);
    sum += static_cast<int>(s.index);
  }
  EXPECT_EQ(sum, 2);
  // Outward at the source: vectors in the faces around vertex 0 point away from it.
  const Eigen::Vector3d p0 = vertexPosition(d.mesh(), 0);
  for (int f = 0; f < d.mesh().numFaces(); ++f)
    for (int c = 0; c < 3; ++c)
      if (d.mesh().triangles[3 * f + c] == 0) EXPECT_GT(faceVector(d, f).dot(centroid(d.mesh(), f) - p0), 0);
}

TEST(Constraints, SingleSourceOnAClosedSurfaceGetsMatchingSinks) {
  Designer d(icosphere(3));
  d.addSource(0, 1.0);
  d.solve();
  double positive = 0;
  for (const auto& s : d.singularities()) positive += s.index;
  EXPECT_EQ(positive, 2.0);
  EXPECT_GE(d.singularities().size(), 2u);  // the source and at least one sink elsewhere
}

TEST(Constraints, ImpossibleInputIsAClearError) {
  Designer d(icosphere(1));
  const double nanVector[3] = {NAN, 0, 0}, u[3] = {1, 0, 0};
  EXPECT_THROW(d.addVector(-1, u, 1.0), InputError);
  EXPECT_THROW(d.addVector(0, nanVector, 1.0), InputError);
  EXPECT_THROW(d.addVector(0, u, 0.0), InputError);
  EXPECT_THROW(d.addSource(100000, 1.0), InputError);
  EXPECT_THROW(d.addEdge(0, 0, 1.0, 1.0), InputError);
  EXPECT_THROW(d.addStroke({{0, {1, 0, 0}}}, 1.0, 1.0), InputError);
  EXPECT_THROW(d.addStroke({{0, {1, 0, 0}}, {9999, {1, 0, 0}}}, 1.0, 1.0), InputError);
  EXPECT_THROW(d.remove(12345), InputError);
  EXPECT_THROW(d.setGamma(-1), InputError);
  try {
    d.addVortex(5000, 1.0);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 5000"), std::string::npos);
  }
  EXPECT_TRUE(d.constraints().empty());
}

TEST(Constraints, SourcesOnAFixedAngleBoundaryAreReported) {
  Designer d(flatGrid(4));
  d.setBoundary(BoundaryCondition::normal());
  d.addSource(0, 1.0);  // a corner: on the boundary
  d.solve();
  ASSERT_EQ(d.stats().warnings.size(), 1u);
  EXPECT_NE(d.stats().warnings[0].find("boundary vertex 0"), std::string::npos);
}

TEST(ConstraintSet, IdsFollowTheOrderOfAddingAndABadConstraintLeavesTheSetUnchanged) {
  const SurfaceMesh m = icosphere(2);
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  ConstraintSet set(m, t, g);
  ConstraintSpec source, vortex, vector;
  source.kind = ConstraintKind::Source;
  source.element = 4;
  vortex.kind = ConstraintKind::Vortex;
  vortex.element = 30;
  vector.kind = ConstraintKind::Vector;
  vector.element = 12;
  vector.vector[0] = 1;
  vector.weight = 2;
  EXPECT_EQ(set.add(source), 1);
  EXPECT_EQ(set.add(vortex), 2);
  set.remove(1);
  vortex.element = 9999;
  EXPECT_THROW(set.add(vortex), InputError);
  EXPECT_EQ(set.add(vector), 3);  // the refused vortex took no id
  const std::vector<ConstraintSpec> specs = set.specs();
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_EQ(specs[0].id, 2);
  EXPECT_EQ(specs[1].id, 3);
  EXPECT_THROW(set.remove(1), InputError);
  EXPECT_THROW(set.setWeight(2, 5.0), InputError);  // a vortex has no weight
  EXPECT_EQ(set.setWeight(3, 5.0), 2.0);
  // A vector in a face is three edge rows, each weighted by weight x scale.
  std::vector<int32_t> rows;
  std::vector<double> weights;
  set.weightedRows(3, 0.5, 4.0, rows, weights);
  ASSERT_EQ(rows.size(), 3u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(rows[c], t.edgeOf(12, c));
    EXPECT_EQ(weights[c], 2.0);
  }
  rows.clear();
  weights.clear();
  set.allWeightedRows(4.0, rows, weights);
  EXPECT_EQ(weights, std::vector<double>(3, 20.0));  // its own weight, 5
}

// The source/sink/vortex part of the right-hand side is kept between solves. After every kind of edit it must
// equal what a set that never cached anything computes for the same constraints, bit for bit (the same
// arithmetic in the same order).
TEST(ConstraintSet, CachedRightHandSideEqualsAFreshSetsAfterEveryEdit) {
  const SurfaceMesh m = flatAnnulus(4, 24, 1, 2);
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  OneFormOperators ops = buildOneFormOperators(m, t, g, boundaryEdgeAngles(t, BoundaryCondition::makeFree()));
  const double scale = 3.0;
  ConstraintSet set(m, t, g);
  Eigen::VectorXd previous = Eigen::VectorXd::Zero(t.numEdges);
  const auto expectFresh = [&](const char* step) {
    ConstraintSet fresh(m, t, g);
    for (const ConstraintSpec& s : set.specs()) fresh.add(s);
    const Eigen::VectorXd cached = set.rightHandSide(ops, scale), eager = fresh.rightHandSide(ops, scale);
    EXPECT_TRUE(cached == eager) << step << ": differs by " << (cached - eager).norm();
    EXPECT_GT((cached - previous).norm(), 1e-6 * cached.norm()) << step << ": the edit changed nothing";
    previous = cached;
  };
  ConstraintSpec source;
  source.kind = ConstraintKind::Source;
  source.element = 30;
  const int32_t sourceId = set.add(source);
  expectFresh("add a source");
  ConstraintSpec stroke;
  stroke.kind = ConstraintKind::Stroke;
  stroke.points = straightStroke(m, {-0.2, 1.5, 0}, {0.2, 1.5, 0}, 8);
  stroke.weight = 10;
  const int32_t strokeId = set.add(stroke);
  expectFresh("add a stroke");
  set.setStrength(sourceId, 2.5);
  expectFresh("a source's strength");
  set.setStrength(strokeId, 0.5);
  expectFresh("a stroke's strength");
  ConstraintSpec vortex;
  vortex.kind = ConstraintKind::Vortex;
  vortex.element = 100;
  vortex.strength = -0.7;
  const int32_t vortexId = set.add(vortex);
  expectFresh("add a vortex");
  set.setWeight(strokeId, 40);
  expectFresh("a stroke's weight");
  set.remove(sourceId);
  expectFresh("remove the source");
  // A fixed-angle boundary takes the boundary vertices out of the divergence operator D: the vortex's part
  // stays, a sink on the boundary would vanish; the cache must follow the new operators.
  ConstraintSpec sink;
  sink.kind = ConstraintKind::Sink;
  sink.element = 0;  // on the inner boundary circle
  ASSERT_TRUE(t.isBoundaryVertex[0]);
  set.add(sink);
  expectFresh("add a sink on the boundary");
  ops = buildOneFormOperators(m, t, g, boundaryEdgeAngles(t, BoundaryCondition::tangential()));
  set.operatorsChanged();
  expectFresh("tangential boundary");
  set.remove(vortexId);
  expectFresh("remove the vortex");
  set.clear();
  EXPECT_EQ(set.rightHandSide(ops, scale).norm(), 0.0);
}
