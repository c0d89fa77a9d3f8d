// Sharp features: the edges detected and edited, the curves they form and the directions they ask of a field.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/input_error.h"
#include "dec/hodge_star.h"
#include "direction/feature_terms.h"
#include "direction/levi_civita_connection.h"
#include "mesh/feature_edges.h"
#include "mesh/icosphere.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

// The unit cube, each side a k x k grid of squares split in two, wound outwards. Vertices sit on the integer
// grid 0..k (scaled by 1/k), which welds the sides and lets the tests tell the cube's edges exactly.
SurfaceMesh box(int k) {
  struct Side {
    std::array<int, 3> origin, u, v;  // u x v is the outward normal
  };
  const Side sides[6] = {{{k, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                         {{0, k, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
                         {{0, 0, k}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}};
  SurfaceMesh m;
  std::map<std::array<int, 3>, int32_t> index;
  const auto vertex = [&](const Side& s, int i, int j) {
    std::array<int, 3> p;
    for (int c = 0; c < 3; ++c) p[c] = s.origin[c] + i * s.u[c] + j * s.v[c];
    const auto inserted = index.emplace(p, m.numVertices());
    if (inserted.second)
      for (int c = 0; c < 3; ++c) m.positions.push_back(static_cast<double>(p[c]) / k);
    return inserted.first->second;
  };
  for (const Side& s : sides)
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const int32_t a = vertex(s, i, j), b = vertex(s, i + 1, j), c = vertex(s, i + 1, j + 1),
                      d = vertex(s, i, j + 1);
        m.triangles.insert(m.triangles.end(), {a, b, c, a, c, d});
      }
  return m;
}

// Two cones of height h on one n-gon rim of radius 1: the rim folds by about 146 degrees (h = 0.3), the fan
// edges by a few, so the rim is one closed crease loop through vertices of feature valence 2.
SurfaceMesh bicone(int n, double h) {
  SurfaceMesh m;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    m.positions.insert(m.positions.end(), {std::cos(a), std::sin(a), 0.0});
  }
  m.positions.insert(m.positions.end(), {0, 0, h, 0, 0, -h});
  for (int i = 0; i < n; ++i) {
    const int32_t j = (i + 1) % n;
    m.triangles.insert(m.triangles.end(), {i, j, n, j, i, n + 1});
  }
  return m;
}

struct Model {
  SurfaceMesh mesh;
  MeshTopology topology;
  MeshGeometry geometry;
  FaceFrames frames;
};

Model model(SurfaceMesh mesh) {
  Model m{std::move(mesh), {}, {}, {}};
  m.topology = buildTopology(m.mesh);
  m.geometry = computeMeshGeometry(m.mesh, m.topology);
  m.frames = faceFrames(m.mesh, m.geometry);
  return m;
}

// How many coordinates of vertex v are at 0 or 1 (a box corner has three, a point of a cube edge two).
int extremeCoordinates(const SurfaceMesh& mesh, int32_t v) {
  int n = 0;
  for (int c = 0; c < 3; ++c) n += mesh.positions[3 * v + c] == 0 || mesh.positions[3 * v + c] == 1;
  return n;
}

// Both ends of e at the same extreme on two axes: e lies on one of the cube's 12 edges.
bool onCubeEdge(const Model& m, int32_t e) {
  const int32_t a = m.topology.edgeVertices[2 * e], b = m.topology.edgeVertices[2 * e + 1];
  int shared = 0;
  for (int c = 0; c < 3; ++c) {
    const double x = m.mesh.positions[3 * a + c], y = m.mesh.positions[3 * b + c];
    shared += x == y && (x == 0 || x == 1);
  }
  return shared >= 2;
}

std::vector<int32_t> edgesWhere(const Model& m, const std::function<bool(int32_t)>& keep) {
  std::vector<int32_t> edges;
  for (int32_t e = 0; e < m.topology.numEdges; ++e)
    if (keep(e)) edges.push_back(e);
  return edges;
}

VertexPair pairOf(const MeshTopology& t, int32_t e) {
  return {t.edgeVertices[2 * e], t.edgeVertices[2 * e + 1]};
}

// The vertices a curve's walk starts and ends each edge at, as its signs say.
int32_t tail(const MeshTopology& t, const FeatureCurve& c, size_t k) {
  return t.edgeVertices[2 * c.edges[k] + (c.signs[k] > 0 ? 0 : 1)];
}
int32_t head(const MeshTopology& t, const FeatureCurve& c, size_t k) {
  return t.edgeVertices[2 * c.edges[k] + (c.signs[k] > 0 ? 1 : 0)];
}

// Each edge's walk ends where the next one's starts (and, closed, the last one's where the first starts).
void expectChained(const MeshTopology& t, const FeatureCurve& c) {
  ASSERT_EQ(c.edges.size(), c.signs.size());
  for (size_t k = 0; k + 1 < c.edges.size(); ++k) EXPECT_EQ(head(t, c, k), tail(t, c, k + 1)) << "edge " << k;
  if (c.closed) EXPECT_EQ(head(t, c, c.edges.size() - 1), tail(t, c, 0));
}

void expectRefused(const std::function<void()>& call, const std::string& named) {
  try {
    call();
    ADD_FAILURE() << "accepted; expected a refusal naming " << named;
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
  }
}

std::string named(const VertexPair& p) {
  return "[" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + "]";
}

Eigen::Vector3d walkDirection(const Model& m, const FeatureCurve& c, size_t k) {
  return (double(c.signs[k]) * edgeVector(m.mesh, m.topology, c.edges[k])).normalized();
}

// The N directions a power value stands for, in 3D.
std::vector<Eigen::Vector3d> rootDirections(const Model& m, const FaceDirectionTerm& term, int symmetry) {
  std::vector<Eigen::Vector3d> roots;
  for (int r = 0; r < symmetry; ++r) {
    Eigen::Vector3d d;
    fromFaceFrame(m.frames, term.face, std::polar(1.0, (std::arg(term.power) + 2 * M_PI * r) / symmetry),
                  d.data());
    roots.push_back(d);
  }
  return roots;
}

bool amongRoots(const std::vector<Eigen::Vector3d>& roots, const Eigen::Vector3d& d) {
  return std::any_of(roots.begin(), roots.end(),
                     [&](const Eigen::Vector3d& r) { return (r - d).norm() < 1e-9; });
}

}  // namespace

TEST(Feature, SharpEdgesOfABoxAreItsTwelveEdgesAndNoneOnItsSides) {
  for (const int k : {1, 3}) {
    const Model m = model(box(k));
    ASSERT_EQ(m.topology.eulerCharacteristic(), 2);
    const std::vector<int32_t> cubeEdges = edgesWhere(m, [&](int32_t e) { return onCubeEdge(m, e); });
    ASSERT_EQ(cubeEdges.size(), 12u * k);
    // The sides fold by 90 degrees, the triangles inside a side by none.
    for (const double degrees : {35.0, 1.0, 89.0})
      EXPECT_EQ(sharpEdges(m.topology, m.geometry, degrees), cubeEdges);
    EXPECT_TRUE(sharpEdges(m.topology, m.geometry, 91).empty());
    EXPECT_TRUE(sharpEdges(m.topology, m.geometry, 0).empty());
    EXPECT_TRUE(featureEdges(m.topology, m.geometry, 0, {}, {}).empty());
  }
}

TEST(Feature, SharpEdgesOfACreaseRingAreTheRim) {
  const Model m = model(bicone(16, 0.3));
  const std::vector<int32_t> rim = edgesWhere(m, [&](int32_t e) {
    return m.mesh.positions[3 * m.topology.edgeVertices[2 * e] + 2] == 0 &&
           m.mesh.positions[3 * m.topology.edgeVertices[2 * e + 1] + 2] == 0;
  });
  ASSERT_EQ(rim.size(), 16u);
  EXPECT_EQ(sharpEdges(m.topology, m.geometry, 35), rim);
}

// A sphere of facets pushed in and out along the normals by a hash of the vertex index (up to `bump` of the
// radius): a scan's or a sculpt's surface, curved at every edge, some of its folds passing 35 degrees.
SurfaceMesh bumpySphere(int subdivisions, double bump) {
  SurfaceMesh m = icosphere(subdivisions);
  for (int32_t v = 0; v < m.numVertices(); ++v) {
    const double h = std::fmod(std::sin(12.9898 * v + 1.0) * 43758.5453, 1.0);  // in (-1, 1)
    for (int c = 0; c < 3; ++c) m.positions[3 * v + c] *= 1 + bump * h;
  }
  return m;
}

TEST(Feature, ABoxIsCreasedAndStartsWithItsEdgesAsFeatures) {
  for (const int k : {1, 3}) {
    const Model m = model(box(k));
    const FoldProfile p = foldProfile(m.mesh, m.topology, m.geometry);
    EXPECT_EQ(p.interiorEdges, m.topology.numEdges);
    EXPECT_EQ(p.sharpEdges, 12 * k);
    EXPECT_EQ(p.gradualEdges, 0);
    EXPECT_EQ(p.longCurveEdges, 12 * k);  // each cube edge a curve from corner to corner
    EXPECT_EQ(suggestedFeatureAngle(p), kSharpFoldDegrees);
  }
}

// A closed cylinder of n sides, height 1 on the unit circle, each cap a fan round its centre.
SurfaceMesh cappedCylinder(int n) {
  SurfaceMesh m;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * 3.14159265358979323846 * k / n;
    for (const double z : {0.0, 1.0}) m.positions.insert(m.positions.end(), {std::cos(a), std::sin(a), z});
  }
  m.positions.insert(m.positions.end(), {0, 0, 0, 0, 0, 1});
  const int32_t bottom = 2 * n, top = 2 * n + 1;
  for (int32_t k = 0; k < n; ++k) {
    const int32_t a = 2 * k, b = 2 * ((k + 1) % n);
    m.triangles.insert(m.triangles.end(), {a, b, b + 1, a, b + 1, a + 1, bottom, b, a, top, a + 1, b + 1});
  }
  return m;
}

TEST(Feature, ACylindersFacetsFoldGraduallyButItsRimsMakeItCreased) {
  // 16 sides: the sides fold by 22.5 degrees (16 of 96 edges), the rims by 90 (32), the rest not at all.
  const Model m = model(cappedCylinder(16));
  const FoldProfile p = foldProfile(m.mesh, m.topology, m.geometry);
  EXPECT_EQ(p.interiorEdges, 96);
  EXPECT_EQ(p.gradualEdges, 16);
  EXPECT_EQ(p.sharpEdges, 32);
  EXPECT_EQ(p.longCurveEdges, 32);  // the two rims, closed loops
  EXPECT_EQ(suggestedFeatureAngle(p), kSharpFoldDegrees);
}

TEST(Feature, AFacetedCurvedSurfaceStartsWithoutFeatures) {
  // Bumps of 4 % on a 642-vertex sphere fold most edges by 3-35 degrees and some (about 100 of 1,920) by
  // more.
  const Model bumpy = model(bumpySphere(3, 0.04));
  const FoldProfile p = foldProfile(bumpy.mesh, bumpy.topology, bumpy.geometry);
  ASSERT_GT(p.sharpEdges, 0);
  ASSERT_LT(p.sharpShare(), kCreasedSharpShare);
  ASSERT_LT(p.longCurveShare(), kCreasedLongCurveShare);  // its sharp edges come in short pieces
  EXPECT_EQ(p.sharpEdges,
            static_cast<int32_t>(sharpEdges(bumpy.topology, bumpy.geometry, kSharpFoldDegrees).size()));
  EXPECT_EQ(suggestedFeatureAngle(p), 0);
  // A smooth sphere folds by a few degrees at most: nothing to follow either.
  const Model smooth = model(icosphere(4));
  const FoldProfile q = foldProfile(smooth.mesh, smooth.topology, smooth.geometry);
  EXPECT_EQ(q.sharpEdges, 0);
  EXPECT_EQ(suggestedFeatureAngle(q), 0);
}

TEST(Feature, TheSharpShareAndTheLongCurvesDecide) {
  // {interior, gradual, sharp, on long curves}. A fifth of the folding edges sharp, some of them on long
  // curves, is creased, whatever the flat edges; so are sharp edges mostly on long curves (a machined part of
  // gentle curves and a few long creases). Sharp edges in pieces are not (a noisy scan).
  EXPECT_EQ(suggestedFeatureAngle(FoldProfile{100, 40, 10, 1}), kSharpFoldDegrees);
  EXPECT_EQ(suggestedFeatureAngle(FoldProfile{10000, 40, 10, 1}), kSharpFoldDegrees);
  EXPECT_EQ(suggestedFeatureAngle(FoldProfile{100, 40, 10, 0}), 0);
  EXPECT_EQ(suggestedFeatureAngle(FoldProfile{100, 41, 10, 5}), 0);
  EXPECT_EQ(suggestedFeatureAngle(FoldProfile{1000, 900, 10, 6}), kSharpFoldDegrees);
  EXPECT_EQ(suggestedFeatureAngle(FoldProfile{100, 0, 0, 0}), 0);
  EXPECT_EQ(suggestedFeatureAngle(FoldProfile{}), 0);
}

TEST(Feature, ASubdividedFacetedSurfaceStillStartsWithoutFeatures) {
  // Each triangle of the bumpy sphere cut in four: the new edges lie flat inside the old facets, the old
  // edges keep their folds, so the profile's folding edges are the old ones twice over.
  const SurfaceMesh coarse = bumpySphere(3, 0.04);
  SurfaceMesh fine;
  fine.positions = coarse.positions;
  std::map<std::pair<int32_t, int32_t>, int32_t> middle;
  const auto mid = [&](int32_t a, int32_t b) {
    const auto key = std::minmax(a, b);
    const auto found = middle.find(key);
    if (found != middle.end()) return found->second;
    const int32_t v = fine.numVertices();
    for (int c = 0; c < 3; ++c)
      fine.positions.push_back(0.5 * (coarse.positions[3 * a + c] + coarse.positions[3 * b + c]));
    middle.emplace(key, v);
    return v;
  };
  for (int32_t f = 0; f < coarse.numFaces(); ++f) {
    const int32_t a = coarse.triangles[3 * f], b = coarse.triangles[3 * f + 1],
                  c = coarse.triangles[3 * f + 2];
    const int32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    fine.triangles.insert(fine.triangles.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  const Model before = model(coarse), after = model(fine);
  const FoldProfile p = foldProfile(before.mesh, before.topology, before.geometry),
                    q = foldProfile(after.mesh, after.topology, after.geometry);
  EXPECT_EQ(q.sharpEdges, 2 * p.sharpEdges);
  EXPECT_EQ(q.gradualEdges, 2 * p.gradualEdges);
  EXPECT_EQ(q.longCurveEdges, 2 * p.longCurveEdges);  // the same curves, each edge in two
  EXPECT_EQ(suggestedFeatureAngle(q), 0);
}

TEST(Feature, AnAngleOutsideZeroTo180IsRefused) {
  const Model m = model(box(2));
  for (const double bad :
       {-1.0, 180.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    expectRefused([&] { sharpEdges(m.topology, m.geometry, bad); }, "feature angle");
    expectRefused([&] { featureEdges(m.topology, m.geometry, bad, {}, {}); }, "feature angle");
  }
  EXPECT_TRUE(sharpEdges(m.topology, m.geometry, 180).empty());
}

TEST(Feature, AddedPairsJoinAndRemovedPairsLeave) {
  const Model m = model(box(3));
  const MeshTopology& t = m.topology;
  const std::vector<int32_t> sharp = sharpEdges(t, m.geometry, 35);
  const std::vector<int32_t> flat = edgesWhere(m, [&](int32_t e) { return !onCubeEdge(m, e); });
  const int32_t added = flat[flat.size() / 2], removed = sharp[5];
  // Pairs in either order; a repeated pair counts once.
  const VertexPair addPair = {t.edgeVertices[2 * added + 1], t.edgeVertices[2 * added]};
  std::vector<int32_t> expected = sharp;
  expected.push_back(added);
  expected.erase(std::find(expected.begin(), expected.end(), removed));
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(featureEdges(t, m.geometry, 35, {addPair, addPair}, {pairOf(t, removed)}), expected);
  // Removal wins over addition, and with detection off only the additions remain.
  EXPECT_EQ(featureEdges(t, m.geometry, 35, {addPair}, {addPair}), sharp);
  EXPECT_EQ(featureEdges(t, m.geometry, 0, {addPair, pairOf(t, removed)}, {}),
            std::vector<int32_t>({std::min(added, removed), std::max(added, removed)}));
  // Removing a pair that is no feature changes nothing.
  EXPECT_EQ(featureEdges(t, m.geometry, 35, {}, {addPair}), sharp);
}

TEST(Feature, PairsThatAreNotInteriorEdgesAreRefusedByName) {
  const Model m = model(box(3));
  const MeshTopology& t = m.topology;
  int32_t far = 1;
  while (findEdge(t, 0, far) >= 0) ++far;
  const int32_t some = t.edgeVertices[0];
  for (const VertexPair& bad : std::vector<VertexPair>{{0, far}, {some, some}, {0, t.numVertices}, {-1, 0}}) {
    expectRefused([&] { featureEdges(t, m.geometry, 35, {bad}, {}); }, named(bad) + " is not a mesh edge");
    expectRefused([&] { featureEdges(t, m.geometry, 35, {}, {bad}); }, named(bad) + " is not a mesh edge");
  }
  const Model open = model(flatGrid(3));
  const std::vector<int32_t> boundary =
      edgesWhere(open, [&](int32_t e) { return open.topology.isBoundaryEdge[e]; });
  ASSERT_FALSE(boundary.empty());
  const VertexPair edge = pairOf(open.topology, boundary[2]);
  expectRefused([&] { featureEdges(open.topology, open.geometry, 0, {edge}, {}); },
                named(edge) + " is a boundary");
  expectRefused([&] { featureEdges(open.topology, open.geometry, 0, {}, {edge}); },
                named(edge) + " is a boundary");
}

TEST(Feature, TheBoxsEdgesAreTwelveOpenCurvesFromCornerToCorner) {
  const int k = 3;
  const Model m = model(box(k));
  const MeshTopology& t = m.topology;
  const std::vector<int32_t> sharp = sharpEdges(t, m.geometry, 35);
  const std::vector<FeatureCurve> curves = featureCurves(t, sharp);
  ASSERT_EQ(curves.size(), 12u);
  std::vector<int32_t> covered;
  for (const FeatureCurve& c : curves) {
    EXPECT_FALSE(c.closed);
    ASSERT_EQ(c.edges.size(), static_cast<size_t>(k));
    expectChained(t, c);
    // Corners (feature valence 3) end curves and nothing else does.
    EXPECT_EQ(extremeCoordinates(m.mesh, tail(t, c, 0)), 3);
    EXPECT_EQ(extremeCoordinates(m.mesh, head(t, c, k - 1)), 3);
    for (size_t i = 0; i + 1 < c.edges.size(); ++i) EXPECT_EQ(extremeCoordinates(m.mesh, head(t, c, i)), 2);
    covered.insert(covered.end(), c.edges.begin(), c.edges.end());
  }
  std::sort(covered.begin(), covered.end());
  EXPECT_EQ(covered, sharp);
}

TEST(Feature, ACreaseRingIsOneClosedCurve) {
  const Model m = model(bicone(16, 0.3));
  const std::vector<int32_t> rim = sharpEdges(m.topology, m.geometry, 35);
  const std::vector<FeatureCurve> curves = featureCurves(m.topology, rim);
  ASSERT_EQ(curves.size(), 1u);
  EXPECT_TRUE(curves[0].closed);
  EXPECT_EQ(curves[0].edges.size(), rim.size());
  expectChained(m.topology, curves[0]);
}

TEST(Feature, AnAddedPathIsOneOpenCurveBetweenItsEnds) {
  // Four edges along the grid's middle row, out of order: the curve starts at the lower end.
  const int n = 6;
  const Model m = model(flatGrid(n));
  const int32_t row = 3 * (n + 1);
  std::vector<VertexPair> path;
  for (const int i : {2, 0, 3, 1}) path.push_back({row + i + 1, row + i + 1 + 1});
  const std::vector<int32_t> edges = featureEdges(m.topology, m.geometry, 0, path, {});
  const std::vector<FeatureCurve> curves = featureCurves(m.topology, edges);
  ASSERT_EQ(curves.size(), 1u);
  EXPECT_FALSE(curves[0].closed);
  ASSERT_EQ(curves[0].edges.size(), 4u);
  expectChained(m.topology, curves[0]);
  EXPECT_EQ(tail(m.topology, curves[0], 0), row + 1);
  EXPECT_EQ(head(m.topology, curves[0], 3), row + 5);
}

TEST(Feature, EachTermLiesAlongItsFeatureEdge) {
  for (const bool ring : {false, true}) {
    const Model m = model(ring ? bicone(16, 0.3) : box(3));
    const std::vector<FeatureCurve> curves =
        featureCurves(m.topology, sharpEdges(m.topology, m.geometry, 35));
    // Per face, the directions its feature edges run in: one, or two at the box's corner triangles.
    std::map<int32_t, std::vector<Eigen::Vector3d>> along;
    size_t edges = 0;
    for (const FeatureCurve& c : curves)
      for (size_t k = 0; k < c.edges.size(); ++k, ++edges)
        for (int side = 0; side < 2; ++side)
          along[m.topology.edgeFaces[2 * c.edges[k] + side]].push_back(walkDirection(m, c, k));
    for (const int symmetry : {1, 2, 3, 4, 6}) {
      const std::vector<FaceDirectionTerm> terms =
          featureDirectionTerms(m.mesh, m.topology, m.frames, curves, symmetry);
      ASSERT_EQ(terms.size(), 2 * edges);
      std::map<int32_t, std::vector<FaceDirectionTerm>> termsAt;
      for (const FaceDirectionTerm& term : terms) {
        EXPECT_NEAR(std::abs(term.power), 1, 1e-12);
        termsAt[term.face].push_back(term);
      }
      for (const auto& face : termsAt)
        EXPECT_EQ(along.count(face.first), 1u) << "terms at face " << face.first << ", beside no feature";
      for (const auto& face : along) {
        const std::vector<FaceDirectionTerm>& at = termsAt[face.first];
        ASSERT_EQ(at.size(), face.second.size()) << "face " << face.first;
        // Some pairing of the face's terms with its edges puts each edge among its term's N roots (for N = 1
        // the walk's own direction only; for even N its reverse too).
        std::vector<size_t> order(at.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = i;
        bool paired = false;
        do {
          bool all = true;
          for (size_t i = 0; i < at.size(); ++i) {
            const std::vector<Eigen::Vector3d> roots = rootDirections(m, at[order[i]], symmetry);
            const Eigen::Vector3d& d = face.second[i];
            all = all && amongRoots(roots, d) && amongRoots(roots, -d) == (symmetry % 2 == 0);
          }
          paired = paired || all;
        } while (std::next_permutation(order.begin(), order.end()));
        EXPECT_TRUE(paired) << "N = " << symmetry << ", face " << face.first;
      }
    }
  }
}

TEST(Feature, VectorTermsRunOneWayAlongEachCurve) {
  // The box: every term on a curve's faces points from the corner the curve starts at to the one it ends at
  // (a corner triangle has two curves, at right angles).
  const Model m = model(box(3));
  const MeshTopology& t = m.topology;
  const std::vector<FeatureCurve> curves = featureCurves(t, sharpEdges(t, m.geometry, 35));
  std::map<int32_t, std::vector<Eigen::Vector3d>> cornerToCorner;
  for (const FeatureCurve& c : curves) {
    const Eigen::Vector3d d =
        (vertexPosition(m.mesh, head(t, c, c.edges.size() - 1)) - vertexPosition(m.mesh, tail(t, c, 0)))
            .normalized();
    for (const int32_t e : c.edges)
      for (int side = 0; side < 2; ++side) cornerToCorner[t.edgeFaces[2 * e + side]].push_back(d);
  }
  for (const FaceDirectionTerm& term : featureDirectionTerms(m.mesh, t, m.frames, curves, 1))
    EXPECT_TRUE(amongRoots(cornerToCorner.at(term.face), rootDirections(m, term, 1)[0])) << term.face;

  // The ring: every term turns the same way about the axis, whichever way the walk chose.
  const Model r = model(bicone(16, 0.3));
  const std::vector<FeatureCurve> ring = featureCurves(r.topology, sharpEdges(r.topology, r.geometry, 35));
  const std::vector<FaceDirectionTerm> terms = featureDirectionTerms(r.mesh, r.topology, r.frames, ring, 1);
  ASSERT_EQ(terms.size(), 32u);
  std::vector<double> turn;
  for (const FaceDirectionTerm& term : terms) {
    Eigen::Vector3d p[3];
    facePositions(r.mesh, term.face, p);
    turn.push_back(((p[0] + p[1] + p[2]) / 3).cross(rootDirections(r, term, 1)[0]).z());
  }
  const auto positive = std::count_if(turn.begin(), turn.end(), [](double z) { return z > 0; });
  EXPECT_TRUE(positive == 0 || positive == static_cast<long>(turn.size()))
      << positive << " of " << turn.size();
  for (const double z : turn) EXPECT_GT(std::abs(z), 0.1);
}
