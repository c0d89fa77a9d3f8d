// The quad remesher (core/quad/) on meshes made here: a torus's singularity-free cross field gives a regular
// grid, a sphere's eight +1/4 cones give eight valence-3 vertices, the Euler characteristic is kept, and the
// statistics match their definitions on polygon meshes built by hand.
#include "quad/quad_remesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "common/input_error.h"
#include "dec/boundary_condition.h"
#include "design/designer.h"
#include "mesh/closest_point.h"
#include "mesh/mesh_geometry.h"
#include "quad/polygon_quadrangulation.h"
#include "quad/quad_mesh_stats.h"
#include "quad/quad_remesh_json.h"
#include "solver/supernodal_cholesky.h"
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

// All quads, none irregular or flipped, and the Euler characteristic chi.
void expectRegular(const QuadRemeshResult& r, int chi) {
  printResult(r);
  EXPECT_EQ(r.stats.irregularVertices, 0);
  EXPECT_EQ(r.stats.quads, r.stats.faces);
  EXPECT_EQ(r.stats.eulerCharacteristic, chi);
  EXPECT_EQ(r.stats.flippedFaces, 0);
}

TEST(QuadRemesh, ATorusWithASingularityFreeCrossFieldIsARegularGrid) {
  Designer d(torus(48, 16, 1.0, 0.35));
  d.setSymmetry(4);
  d.setExactSingularities(true);
  d.solve();
  ASSERT_TRUE(d.singularities().empty());
  const QuadRemeshResult r = remeshDesign(d, 0.1);
  expectRegular(r, 0);
  EXPECT_EQ(r.stats.boundaryEdges, 0);
  EXPECT_TRUE(r.stats.manifold);
  EXPECT_TRUE(r.stats.oriented);
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
  // The last cones' closure equations come out with even coefficients; divided by 2 they are kept too.
  EXPECT_EQ(r.unenforcedConditions, 0);
  EXPECT_EQ(r.stats.valence3, 8);
  EXPECT_EQ(r.stats.irregularVertices, 8);
  EXPECT_EQ(r.stats.quads, r.stats.faces);
  EXPECT_EQ(r.stats.eulerCharacteristic, 2);
  EXPECT_EQ(r.stats.flippedFaces, 0);
}

// The unit cube's surface as an n x n quad grid per side (a hand-made quad mesh: 6 n^2 quads, the corners of
// valence 3), and the same grid split into triangles as the input surface it lies on.
struct CubeQuads {
  QuadMesh quads;
  SurfaceMesh surface;
  std::vector<double> axisField;  // 3 per triangle: a cube edge's direction in its plane
  std::vector<Singularity> corners;
};

CubeQuads cubeQuads(int n) {
  CubeQuads c;
  std::map<std::array<long, 3>, int32_t> index;
  auto vertex = [&](const Eigen::Vector3d& x) {
    const std::array<long, 3> key{std::lround(x.x() * n), std::lround(x.y() * n), std::lround(x.z() * n)};
    const auto [it, added] = index.emplace(key, static_cast<int32_t>(index.size()));
    if (added) c.quads.positions.insert(c.quads.positions.end(), {x.x(), x.y(), x.z()});
    return it->second;
  };
  c.quads.faceStart.push_back(0);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      // Two tangent axes ordered so that (a, b, outward normal) is right-handed.
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          int32_t q[4];
          const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            Eigen::Vector3d x = Eigen::Vector3d::Zero();
            x[axis] = side;
            x[a] = static_cast<double>(i + di[k]) / n;
            x[b] = static_cast<double>(j + dj[k]) / n;
            q[k] = vertex(x);
          }
          if (side == 0) std::swap(q[1], q[3]);
          c.quads.faceVertices.insert(c.quads.faceVertices.end(), q, q + 4);
          c.quads.faceStart.push_back(static_cast<int32_t>(c.quads.faceVertices.size()));
          c.surface.triangles.insert(c.surface.triangles.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
          Eigen::Vector3d along = Eigen::Vector3d::Zero();
          along[a] = 1;
          for (int t = 0; t < 2; ++t)
            c.axisField.insert(c.axisField.end(), {along.x(), along.y(), along.z()});
        }
    }
  c.surface.positions = c.quads.positions;
  c.quads.vertexFace.assign(c.quads.numVertices(), -1);
  for (std::size_t t = 0; t < c.surface.triangles.size(); ++t)
    if (c.quads.vertexFace[c.surface.triangles[t]] < 0)
      c.quads.vertexFace[c.surface.triangles[t]] = static_cast<int32_t>(t / 3);
  for (const auto& [key, v] : index)
    if ((key[0] == 0 || key[0] == n) && (key[1] == 0 || key[1] == n) && (key[2] == 0 || key[2] == n))
      c.corners.push_back({v, 0.25});
  return c;
}

QuadMeshStats measureCube(const CubeQuads& c, double h) {
  const MeshTopology t = buildTopology(c.surface);
  const MeshGeometry g = computeMeshGeometry(c.surface, t);
  return measureQuadMesh(c.quads, c.surface, g, c.axisField, 4, c.corners, h);
}

// The grid's distance against every triangle's, at points on, near and far from a torus; with a bound, the
// exact distance wherever it is beyond the bound and at most the bound elsewhere (the Hausdorff distance's
// early stop).
TEST(TriangleGrid, DistancesAgreeWithEveryTriangleAndABoundStopsOnlyWithinIt) {
  const SurfaceMesh m = torus(24, 12, 1.0, 0.3);
  const TriangleGrid grid(m.positions, m.triangles);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0), bound(0.0, 0.5);
  int beyond = 0, within = 0;
  for (int k = 0; k < 400; ++k) {
    const Eigen::Vector3d p(coordinate(rng), coordinate(rng), 0.5 * coordinate(rng));
    double exact = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < m.triangles.size(); t += 3) {
      const Eigen::Vector3d a(&m.positions[3 * m.triangles[t]]), b(&m.positions[3 * m.triangles[t + 1]]),
          c(&m.positions[3 * m.triangles[t + 2]]);
      exact = std::min(exact, (closestPointOnTriangle(p, a, b, c) - p).norm());
    }
    EXPECT_NEAR(grid.distance(p), exact, 1e-12);
    const double b = bound(rng), bounded = grid.distance(p, b);
    if (exact > b) {
      EXPECT_NEAR(bounded, exact, 1e-12);
      ++beyond;
    } else {
      EXPECT_LE(bounded, b);
      EXPECT_GE(bounded, exact - 1e-12);
      ++within;
    }
  }
  EXPECT_GT(beyond, 50);
  EXPECT_GT(within, 50);
}

TEST(QuadMeshStats, AHandMadeCubeGridMeasuresAsItsDefinitionsSay) {
  const CubeQuads c = cubeQuads(3);
  const QuadMeshStats s = measureCube(c, 1.0 / 3);
  EXPECT_EQ(s.faces, 54);
  EXPECT_EQ(s.quads, 54);
  EXPECT_DOUBLE_EQ(s.quadShare, 1.0);
  EXPECT_EQ(s.vertices, 56);  // 6 n^2 + 2 for n = 3 (V - E + F = 2 with E = 2 F)
  EXPECT_EQ(s.eulerCharacteristic, 2);
  EXPECT_EQ(s.irregularVertices, 8);
  EXPECT_EQ(s.valence3, 8);
  EXPECT_DOUBLE_EQ(s.irregularNearSingularity, 1.0);
  EXPECT_NEAR(s.irregularFarthest, 0.0, 1e-12);
  EXPECT_EQ(s.crowdedSingularities, 0);  // the corners are an edge of the cube (3 h) apart
  // Quads longer than the cube's edge: every corner has another closer than a quad.
  EXPECT_EQ(measureCube(c, 1.01).crowdedSingularities, 8);
  EXPECT_EQ(measureCube(c, 0.99).crowdedSingularities, 0);
  EXPECT_NEAR(s.edgeAngleMedianDeg, 0.0, 1e-9);
  EXPECT_NEAR(s.edgeAngleP90Deg, 0.0, 1e-9);
  EXPECT_NEAR(s.hausdorffRelative, 0.0, 1e-12);
  EXPECT_NEAR(s.aspectMedian, 1.0, 1e-12);
  EXPECT_EQ(s.flippedFaces, 0);
  EXPECT_EQ(s.degenerateFaces, 0);
  EXPECT_TRUE(s.manifold);
  EXPECT_TRUE(s.oriented);
  EXPECT_EQ(s.boundaryEdges, 0);
}

TEST(QuadMeshStats, FlipsDegeneraciesHolesDistancesAndAnglesAreCounted) {
  CubeQuads c = cubeQuads(3);
  // One quad reversed: it points inwards and its edges run the same way as its neighbours'.
  std::reverse(c.quads.faceVertices.begin() + 4, c.quads.faceVertices.begin() + 8);
  QuadMeshStats s = measureCube(c, 1.0 / 3);
  EXPECT_EQ(s.flippedFaces, 1);
  EXPECT_FALSE(s.oriented);
  // One quad removed: a hole of four edges; and the singularities moved away from the corners.
  c = cubeQuads(3);
  c.quads.faceVertices.erase(c.quads.faceVertices.begin(), c.quads.faceVertices.begin() + 4);
  c.quads.faceStart.erase(c.quads.faceStart.begin());
  for (int32_t& k : c.quads.faceStart) k -= 4;
  for (Singularity& x : c.corners) x.vertex = c.corners.front().vertex;
  s = measureCube(c, 1.0 / 3);
  EXPECT_EQ(s.faces, 53);
  EXPECT_EQ(s.boundaryEdges, 4);
  EXPECT_EQ(s.eulerCharacteristic, 1);
  EXPECT_LT(s.irregularNearSingularity, 1.0);
  EXPECT_NEAR(s.irregularFarthest, 3 * std::sqrt(3.0), 1e-9);  // the opposite corner: sqrt(3) / h
  EXPECT_EQ(s.crowdedSingularities, 8);                        // all eight at one vertex
  // A quad with a vertex twice is degenerate.
  c = cubeQuads(3);
  c.quads.faceVertices[c.quads.faceStart[1] + 2] = c.quads.faceVertices[c.quads.faceStart[1] + 1];
  s = measureCube(c, 1.0 / 3);
  EXPECT_EQ(s.degenerateFaces, 1);
  // The field turned by 10 degrees in every face: every edge is 10 degrees off.
  c = cubeQuads(3);
  const MeshTopology t = buildTopology(c.surface);
  const MeshGeometry g = computeMeshGeometry(c.surface, t);
  for (int32_t f = 0; f < t.numFaces; ++f) {
    const Eigen::Vector3d n(&g.faceNormal[3 * f]), x(&c.axisField[3 * f]);
    const double a = 10 * M_PI / 180;
    Eigen::Map<Eigen::Vector3d>(&c.axisField[3 * f]) = std::cos(a) * x + std::sin(a) * n.cross(x);
  }
  s = measureQuadMesh(c.quads, c.surface, g, c.axisField, 4, c.corners, 1.0 / 3);
  EXPECT_NEAR(s.edgeAngleMedianDeg, 10.0, 1e-9);
  EXPECT_NEAR(s.edgeAngleP90Deg, 10.0, 1e-9);
}

// Faces f and g, which share an edge, made one polygon (the rest renumbered): a hole as the extraction closes
// it where walks failed.
void mergeFaces(QuadMesh& m, int32_t f, int32_t g) {
  auto corners = [&](int32_t h) {
    return std::vector<int32_t>(m.faceVertices.begin() + m.faceStart[h],
                                m.faceVertices.begin() + m.faceStart[h + 1]);
  };
  const std::vector<int32_t> a = corners(f), b = corners(g);
  std::vector<int32_t> loop;
  for (std::size_t i = 0; i < a.size() && loop.empty(); ++i) {
    const int32_t x = a[i], y = a[(i + 1) % a.size()];
    const auto at = std::find(b.begin(), b.end(), y);
    if (at == b.end() || b[(at - b.begin() + 1) % b.size()] != x) continue;
    for (std::size_t k = 1; k <= a.size(); ++k) loop.push_back(a[(i + k) % a.size()]);  // y ... round to x
    for (std::size_t k = 1; k + 1 < b.size(); ++k) loop.push_back(b[(at - b.begin() + 1 + k) % b.size()]);
  }
  ASSERT_FALSE(loop.empty()) << "faces " << f << " and " << g << " share no edge";
  std::vector<int32_t> start{0}, vertices;
  for (int32_t h = 0; h < m.numFaces(); ++h) {
    if (h == g) continue;
    const std::vector<int32_t> c = h == f ? loop : corners(h);
    vertices.insert(vertices.end(), c.begin(), c.end());
    start.push_back(static_cast<int32_t>(vertices.size()));
  }
  m.faceStart = std::move(start);
  m.faceVertices = std::move(vertices);
}

// Where the grid folded the extraction closes a hole by one polygon; its corners that lost a grid line have
// valence 3 although the grid is regular there. The split joins them again: the cube's grid comes back whole.
TEST(PolygonQuadrangulation, AHoleInARegularGridIsSplitBackIntoItsQuads) {
  for (int merged : {2, 3}) {
    CubeQuads c = cubeQuads(4);
    // Quads (i, 1), (i, 2) [, (i, 3)] of the first side: a strip of `merged` quads, a 6- or 8-gon.
    for (int k = 1; k < merged; ++k) mergeFaces(c.quads, 4 + 1, 4 + 2);
    ASSERT_EQ(c.quads.numFaces(), 96 - merged + 1);
    const QuadMeshStats before = measureCube(c, 0.25);
    EXPECT_EQ(before.irregularVertices, 8 + 2 * (merged - 1));  // each missing edge's two ends
    EXPECT_EQ(quadrangulatePolygons(c.quads, c.surface), 1);
    const QuadMeshStats after = measureCube(c, 0.25);
    EXPECT_EQ(after.faces, 96);
    EXPECT_EQ(after.quads, 96);
    EXPECT_EQ(after.irregularVertices, 8);  // the cube's corners alone
    EXPECT_EQ(after.eulerCharacteristic, 2);
    EXPECT_TRUE(after.manifold);
    EXPECT_TRUE(after.oriented);
    EXPECT_EQ(after.flippedFaces, 0);
    EXPECT_NEAR(after.aspectMedian, 1.0, 1e-12);
    // The same grid as before the merge: every quad's corners a unit square of the grid.
    const CubeQuads whole = cubeQuads(4);
    std::set<std::set<int32_t>> quadsBefore, quadsAfter;
    for (int32_t f = 0; f < 96; ++f) {
      quadsBefore.insert({whole.quads.faceVertices.begin() + whole.quads.faceStart[f],
                          whole.quads.faceVertices.begin() + whole.quads.faceStart[f + 1]});
      quadsAfter.insert({c.quads.faceVertices.begin() + c.quads.faceStart[f],
                         c.quads.faceVertices.begin() + c.quads.faceStart[f + 1]});
    }
    EXPECT_EQ(quadsAfter, quadsBefore);
  }
}

// An odd polygon (a triangle and two quads merged: 7 corners) becomes two quads and a triangle, with no more
// irregular vertices than before the merge.
TEST(PolygonQuadrangulation, AnOddPolygonIsSplitIntoQuadsAndOneTriangle) {
  CubeQuads c = cubeQuads(4);
  // Quad (1, 0) of the first side as two triangles, the first of them beside quad (1, 1).
  const int32_t* q = &c.quads.faceVertices[c.quads.faceStart[4]];
  const std::vector<int32_t> t1{q[0], q[1], q[2]}, t2{q[0], q[2], q[3]};
  std::vector<int32_t> vertices(c.quads.faceVertices.begin(), c.quads.faceVertices.begin() + 16);
  std::vector<int32_t> start(c.quads.faceStart.begin(), c.quads.faceStart.begin() + 5);
  vertices.insert(vertices.end(), t1.begin(), t1.end());
  start.push_back(static_cast<int32_t>(vertices.size()));
  vertices.insert(vertices.end(), t2.begin(), t2.end());
  start.push_back(static_cast<int32_t>(vertices.size()));
  for (int32_t f = 5; f < 96; ++f) {
    vertices.insert(vertices.end(), c.quads.faceVertices.begin() + c.quads.faceStart[f],
                    c.quads.faceVertices.begin() + c.quads.faceStart[f + 1]);
    start.push_back(static_cast<int32_t>(vertices.size()));
  }
  c.quads.faceVertices = vertices, c.quads.faceStart = start;
  const int32_t irregularWithTriangles = measureCube(c, 0.25).irregularVertices;
  // The triangle t1 (face 4), quad (1, 1) (face 6) and quad (1, 2) (face 7).
  mergeFaces(c.quads, 6, 7);
  mergeFaces(c.quads, 4, 6);
  ASSERT_EQ(c.quads.faceStart[5] - c.quads.faceStart[4], 7);
  EXPECT_EQ(quadrangulatePolygons(c.quads, c.surface), 1);
  const QuadMeshStats s = measureCube(c, 0.25);
  EXPECT_EQ(s.faces, 97);
  EXPECT_EQ(s.quads, 95);
  EXPECT_LE(s.irregularVertices, irregularWithTriangles);
  EXPECT_TRUE(s.manifold);
  EXPECT_EQ(s.flippedFaces, 0);
  EXPECT_EQ(s.degenerateFaces, 0);
  EXPECT_EQ(s.eulerCharacteristic, 2);
}

TEST(QuadRemesh, KeepsTheEulerCharacteristicOfAGenusTwoSurface) {
  Designer d(testing::holedPlate(5, 3, {{1, 1}, {3, 1}}, 2));
  d.setSymmetry(4);
  d.solve();
  const QuadRemeshResult r = remeshDesign(d, 0.25);
  printResult(r);
  EXPECT_EQ(r.stats.eulerCharacteristic, -2);
  EXPECT_EQ(r.unenforcedConditions, 0);
  EXPECT_EQ(r.stats.boundaryEdges, 0);
  EXPECT_GE(r.stats.quadShare, 0.98);
  EXPECT_LT(r.stats.edgeAngleMedianDeg, 5.0);
}

// The quad mesh's edges with one face (its boundary), as vertex pairs.
std::vector<std::pair<int32_t, int32_t>> quadBoundaryEdges(const QuadMesh& q) {
  std::map<std::pair<int32_t, int32_t>, int> count;
  for (int32_t f = 0; f < q.numFaces(); ++f)
    for (int32_t k = q.faceStart[f]; k < q.faceStart[f + 1]; ++k) {
      const int32_t a = q.faceVertices[k],
                    b = q.faceVertices[k + 1 < q.faceStart[f + 1] ? k + 1 : q.faceStart[f]];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<std::pair<int32_t, int32_t>> out;
  for (const auto& [e, n] : count)
    if (n == 1) out.push_back(e);
  return out;
}

Eigen::Vector3d quadVertex(const QuadMesh& q, int32_t v) {
  return Eigen::Vector3d(&q.positions[3 * v]);
}

// A square's regular n x n grid of quads: its boundary 4 n edges, a disc.
void expectSquareGrid(const QuadRemeshResult& r, int n) {
  printResult(r);
  EXPECT_EQ(r.stats.faces, n * n);
  EXPECT_EQ(r.stats.quads, n * n);
  EXPECT_EQ(r.stats.irregularVertices, 0);
  EXPECT_EQ(r.stats.boundaryEdges, 4 * n);
  EXPECT_EQ(r.stats.eulerCharacteristic, 1);
  EXPECT_EQ(r.failedTraces, 0);
  EXPECT_NEAR(r.stats.aspectMedian, 1.0, 1e-6);
}

void expectFlatSquareGrid() {
  Designer d(testing::flatGrid(12));
  d.setSymmetry(4);
  d.setBoundary(BoundaryCondition::tangential());
  d.solve();
  // 1 / 0.09 = 11.1: the grid stretches to whole quads between the sides, as the sides are iso-lines.
  const QuadRemeshResult r = remeshDesign(d, 0.09);
  expectSquareGrid(r, 11);
  EXPECT_EQ(r.filledHoles, 0);
  EXPECT_EQ(r.stats.flippedFaces, 0);
  EXPECT_TRUE(r.stats.oriented);
  EXPECT_NEAR(r.stats.edgeAngleMedianDeg, 0.0, 1e-6);
  // Every edge of the quad mesh's boundary lies on the square's, and its four corners are quad vertices.
  auto onSide = [](double x) { return std::abs(x) < 1e-9 || std::abs(x - 1) < 1e-9; };
  for (const auto& [a, b] : quadBoundaryEdges(r.mesh)) {
    const Eigen::Vector3d p = quadVertex(r.mesh, a), q = quadVertex(r.mesh, b);
    EXPECT_TRUE((onSide(p.x()) && std::abs(p.x() - q.x()) < 1e-9) ||
                (onSide(p.y()) && std::abs(p.y() - q.y()) < 1e-9))
        << p.transpose() << " - " << q.transpose();
  }
  int corners = 0;
  for (int32_t v = 0; v < r.mesh.numVertices(); ++v)
    corners += onSide(quadVertex(r.mesh, v).x()) && onSide(quadVertex(r.mesh, v).y());
  EXPECT_EQ(corners, 4);
}

// Whichever factorization solves the parametrization (the project's, CHOLMOD's: their round-off differs), the
// grid points on the tessellation's diagonals (u = v here) are found once each.
TEST(QuadRemesh, AFlatSquareWithItsBoundaryFollowedIsARegularGridWithTheSameBoundary) {
  for (const bool own : {true, false}) {
    SCOPED_TRACE(own ? "the project's factorization" : "CHOLMOD's factorization");
    const bool before = setOwnFactorizationAlone(own);
    expectFlatSquareGrid();
    setOwnFactorizationAlone(before);
  }
}

TEST(QuadRemesh, AGridThroughTheTessellationsOwnVerticesAndEdgesIsWhole) {
  // 8 x 8 cells a side of 2, quads of 0.45: four a side, their lines at 0.5, 1 and 1.5 run along the cells'
  // edges and cross at their vertices, up to round-off.
  Designer d(testing::flatGrid(8, 2.0));
  d.setSymmetry(4);
  d.setBoundary(BoundaryCondition::tangential());
  d.solve();
  expectSquareGrid(remeshDesign(d, 0.45), 4);
}

TEST(QuadRemesh, AnAnnulusFollowingItsCirclesIsARegularGridBetweenThem) {
  Designer d(testing::flatAnnulus(8, 64, 0.5, 1.0));
  d.setSymmetry(4);
  d.setBoundary(BoundaryCondition::tangential());
  d.solve();
  ASSERT_TRUE(d.singularities().empty());
  const QuadRemeshResult r = remeshDesign(d, 0.1);
  expectRegular(r, 0);
  EXPECT_EQ(r.failedTraces, 0);
  // Both circles are the quad mesh's boundary: its vertices there lie on them.
  const std::vector<std::pair<int32_t, int32_t>> boundary = quadBoundaryEdges(r.mesh);
  EXPECT_EQ(static_cast<int32_t>(boundary.size()), r.stats.boundaryEdges);
  for (const auto& [a, b] : boundary)
    for (int32_t v : {a, b}) {
      // On the 64-gon: between its inscribed circle (cos(pi / 64) r) and its corners (r).
      const double radius = quadVertex(r.mesh, v).head<2>().norm(), inner = std::cos(M_PI / 64) - 1e-9;
      EXPECT_TRUE((radius >= 0.5 * inner && radius <= 0.5 + 1e-9) || (radius >= inner && radius <= 1 + 1e-9))
          << radius;
    }
}

TEST(QuadRemesh, ACubesSharpEdgesBecomeChainsOfQuadEdges) {
  // The cube's surface, 8 triangle pairs a side; its 12 edges are features at 35 degrees.
  Designer d(cubeQuads(8).surface);
  d.setSymmetry(4);
  d.setFeatures(35, {}, {});
  d.solve();
  ASSERT_EQ(d.featureEdges().size(), 12u * 8);
  QuadRemeshOptions o;
  o.edgeLength = 0.3;  // 3.33 a side: the sides' lines make it 3
  for (int32_t e : d.featureEdges())
    for (int k = 0; k < 2; ++k) o.featureEdges.push_back(d.topology().edgeVertices[2 * e + k]);
  const QuadRemeshResult r = quadRemesh(d.mesh(), d.topology(), d.geometry(), d.faceVectors(), 4, o);
  printResult(r);
  EXPECT_EQ(r.stats.faces, 54);
  EXPECT_EQ(r.stats.quads, 54);
  EXPECT_EQ(r.stats.valence3, 8);
  EXPECT_EQ(r.stats.irregularVertices, 8);
  EXPECT_EQ(r.stats.eulerCharacteristic, 2);
  EXPECT_NEAR(r.stats.hausdorffRelative, 0.0, 1e-9);
  // Each quad lies in one side of the cube: no quad folds over a sharp edge.
  for (int32_t f = 0; f < r.mesh.numFaces(); ++f) {
    bool inOneSide = false;
    for (int axis = 0; axis < 3; ++axis)
      for (double side : {0.0, 1.0}) {
        bool all = true;
        for (int32_t k = r.mesh.faceStart[f]; k < r.mesh.faceStart[f + 1]; ++k)
          all = all && std::abs(quadVertex(r.mesh, r.mesh.faceVertices[k])[axis] - side) < 1e-9;
        inOneSide = inOneSide || all;
      }
    EXPECT_TRUE(inOneSide) << "quad " << f;
  }
}

QuadRemeshResult remeshWithFeatures(Designer& d, double edgeLength) {
  QuadRemeshOptions o;
  o.edgeLength = edgeLength;
  for (int32_t e : d.featureEdges())
    for (int k = 0; k < 2; ++k) o.featureEdges.push_back(d.topology().edgeVertices[2 * e + k]);
  return quadRemesh(d.mesh(), d.topology(), d.geometry(), d.faceVectors(), 4, o);
}

TEST(QuadRemesh, CreasesCloserThanAQuadAreLetGoAndTheRestFollowed) {
  // A torus of hexagonal section: six creases round it, 0.35 apart.
  Designer d(torus(48, 6, 1.0, 0.35));
  d.setSymmetry(4);
  d.setFeatures(35, {}, {});
  d.solve();
  ASSERT_EQ(d.featureEdges().size(), 6u * 48);
  const QuadRemeshResult fine = remeshWithFeatures(d, 0.1);
  expectRegular(fine, 0);
  EXPECT_EQ(fine.featureCurves, 6);
  EXPECT_EQ(fine.releasedFeatureCurves, 0);
  // At 0.6 the six creases cannot all be grid lines (the section's 2.1 would need six quads): some are let
  // go, and the grid is still whole.
  const QuadRemeshResult coarse = remeshWithFeatures(d, 0.6);
  expectRegular(coarse, 0);
  EXPECT_GT(coarse.releasedFeatureCurves, 0);
  EXPECT_EQ(coarse.flippedTriangles, 0);
}

TEST(QuadRemesh, RefusesWhatItCannotMeshByName) {
  Designer line(icosphere(2));
  line.setSymmetry(2);
  line.solve();
  try {
    remeshDesign(line, 0.2);
    FAIL() << "a line field was remeshed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Quad meshes need a cross field"), std::string::npos) << e.what();
  }
  Designer sphere(icosphere(2));
  sphere.setSymmetry(4);
  sphere.solve();
  EXPECT_THROW(remeshDesign(sphere, 1e-5), InputError);  // far more than 4 million quads
  EXPECT_THROW(remeshDesign(sphere, -1), InputError);
  QuadRemeshOptions notAnEdge;
  notAnEdge.edgeLength = 0.2;
  notAnEdge.featureEdges = {0, 0};
  try {
    quadRemesh(sphere.mesh(), sphere.topology(), sphere.geometry(), sphere.faceVectors(), 4, notAnEdge);
    FAIL() << "a feature pair that is no edge was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is not an edge"), std::string::npos) << e.what();
  }
  // A vertex index past 32 bits is refused, not wrapped round to another vertex.
  EXPECT_THROW(quadRemeshOptionsFromJson(R"({"featureEdges": [4294967296, 1]})"), InputError);
  EXPECT_EQ(quadRemeshOptionsFromJson(R"({"featureEdges": [3, 4]})").featureEdges,
            (std::vector<int32_t>{3, 4}));
  // A Cancel from the progress callback ends it with RemeshCancelled.
  QuadRemeshOptions o;
  o.edgeLength = 0.2;
  EXPECT_THROW(quadRemesh(sphere.mesh(), sphere.topology(), sphere.geometry(), sphere.faceVectors(), 4, o,
                          [](const std::string& stage, double) { return stage != "extracting"; }),
               RemeshCancelled);
}

}  // namespace
}  // namespace tvf
