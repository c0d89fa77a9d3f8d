// Topology and mesh checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "dec/hodge_star.h"
#include "design/designer.h"
#include "design/mesh_info.h"
#include "mesh/face_adjacency.h"
#include "mesh/mesh_checks.h"
#include "mesh/mesh_geometry.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

TEST(Topology, EulerCharacteristicGenusAndBoundaryLoops) {
  struct Case {
    SurfaceMesh mesh;
    int chi, genus, loops, components;
  };
  const std::vector<Case> cases = {
      {icosphere(1), 2, 0, 0, 1},
      {torus(10, 6, 2, 0.7), 0, 1, 0, 1},
      {holedPlate(7, 3, {{1, 1}, {3, 1}, {5, 1}}, 1), -4, 3, 0, 1},
      {flatAnnulus(3, 12, 1, 2), 0, 0, 2, 1},
      {flatGrid(4), 1, 0, 1, 1},
      {disjointUnion(icosphere(0), flatGrid(3)), 3, 0, 1, 2},
  };
  for (const Case& c : cases) {
    const MeshReport r = checkMesh(c.mesh);
    ASSERT_TRUE(r.usable()) << r.firstFatal();
    const MeshTopology& t = *r.topology;
    EXPECT_EQ(t.eulerCharacteristic(), c.chi);
    int genus = 0;
    for (const auto& comp : t.components) genus += comp.genus;
    EXPECT_EQ(genus, c.genus);
    EXPECT_EQ(static_cast<int>(t.boundaryLoops.size()), c.loops);
    EXPECT_EQ(static_cast<int>(t.components.size()), c.components);
  }
}

TEST(Topology, EdgesAreCanonicallyOrientedAndSignsMatchFaces) {
  const SurfaceMesh m = torus(6, 5, 2, 0.7);
  const MeshTopology t = buildTopology(m);
  EXPECT_EQ(t.numEdges, 3 * m.numFaces() / 2);
  for (int e = 0; e < t.numEdges; ++e) EXPECT_LT(t.edgeVertices[2 * e], t.edgeVertices[2 * e + 1]);
  for (int f = 0; f < t.numFaces; ++f)
    for (int c = 0; c < 3; ++c) {
      const int e = t.edgeOf(f, c), a = m.triangles[3 * f + c], b = m.triangles[3 * f + (c + 1) % 3];
      EXPECT_EQ(t.signOf(f, c), a == t.edgeVertices[2 * e] ? 1 : -1);
      EXPECT_EQ(std::min(a, b), t.edgeVertices[2 * e]);
    }
}

// The edges as a sort of every corner's (lower, upper, corner) key numbers them: the canonical order the
// linear-time build must reproduce exactly (edge ids are the 1-form's unknowns, saved in field files).
TEST(Topology, EdgeNumberingEqualsASortOfAllCornerKeys) {
  SurfaceMesh shuffled = torus(9, 7, 2, 0.7);
  // Faces in a scrambled order and vertices renumbered, so that neither follows the other.
  const int32_t nF = shuffled.numFaces(), nV = shuffled.numVertices();
  std::vector<int32_t> tri(shuffled.triangles.size());
  for (int32_t f = 0; f < nF; ++f)
    for (int c = 0; c < 3; ++c) tri[3 * f + c] = (shuffled.triangles[3 * ((f * 37) % nF) + c] * 11) % nV;
  shuffled.triangles = tri;
  SurfaceMesh book = flatGrid(3);
  book.triangles.insert(book.triangles.end(), {0, 1, 5, 1, 0, 6});  // edge (0, 1) on three, then four faces
  for (const SurfaceMesh& m : {shuffled, book, holedPlate(7, 3, {{1, 1}, {3, 1}}, 1)}) {
    std::vector<std::array<int64_t, 3>> keys;
    for (int32_t h = 0; h < static_cast<int32_t>(m.triangles.size()); ++h) {
      const int32_t a = m.triangles[h], b = m.triangles[h - h % 3 + (h % 3 + 1) % 3];
      keys.push_back({std::min(a, b), std::max(a, b), h});
    }
    std::sort(keys.begin(), keys.end());
    const MeshTopology t = buildTopology(m);
    int32_t e = -1;
    std::vector<int32_t> count;
    for (size_t k = 0; k < keys.size(); ++k) {
      if (k == 0 || keys[k][0] != keys[k - 1][0] || keys[k][1] != keys[k - 1][1]) {
        ++e;
        ASSERT_LT(e, t.numEdges);
        EXPECT_EQ(t.edgeVertices[2 * e], keys[k][0]);
        EXPECT_EQ(t.edgeVertices[2 * e + 1], keys[k][1]);
        count.push_back(0);
      }
      const int32_t h = static_cast<int32_t>(keys[k][2]);
      EXPECT_EQ(t.faceEdges[h], e);
      if (count[e] < 2)
        EXPECT_EQ(t.edgeFaces[2 * e + count[e]], h / 3) << "the corners of an edge in corner order";
      ++count[e];
    }
    EXPECT_EQ(e + 1, t.numEdges);
    for (int32_t k = 0; k <= e; ++k) EXPECT_EQ(t.edgeFaceCount[k], count[k]);
  }
}

namespace {
std::string firstFatal(const SurfaceMesh& m) {
  return checkMesh(m).firstFatal();
}
}  // namespace

// The picking's adjacency from the topology: each half-edge's twin runs between the same two vertices the
// other way, twins pair up, and only boundary edges have none; each face is listed at its three vertices, in
// face order; the normals are unit, along p01 x p02, and (0, 0, 1) on a face of zero area.
TEST(FaceAdjacency, TwinsFacesRoundVerticesAndNormalsFollowTheTriangles) {
  SurfaceMesh m = disjointUnion(torus(7, 5, 2, 0.7), flatAnnulus(3, 12, 1, 2));
  const int32_t nV = m.numVertices();
  m.positions.insert(m.positions.end(), {5, 5, 5, 6, 6, 6, 7, 7, 7});  // a face of zero area, on a line
  m.triangles.insert(m.triangles.end(), {nV, nV + 1, nV + 2});
  const MeshTopology t = buildTopology(m);
  const std::vector<int32_t> twin = halfEdgeTwins(t);
  const std::vector<int32_t>& T = m.triangles;
  const auto to = [&](int32_t h) { return T[h - h % 3 + (h % 3 + 1) % 3]; };
  int boundary = 0;
  for (int32_t h = 0; h < static_cast<int32_t>(T.size()); ++h) {
    if (twin[h] < 0) {
      ++boundary;
      EXPECT_TRUE(t.isBoundaryEdge[t.faceEdges[h]]) << h;
      continue;
    }
    EXPECT_EQ(twin[twin[h]], h);
    EXPECT_NE(twin[h] / 3, h / 3);
    EXPECT_EQ(T[twin[h]], to(h));
    EXPECT_EQ(to(twin[h]), T[h]);
  }
  EXPECT_EQ(boundary, 12 + 12 + 3);  // the annulus's two loops and the lone face's three edges
  const VertexFaces round = vertexFaces(m, m.numVertices());
  ASSERT_EQ(round.start.back(), static_cast<int32_t>(T.size()));
  for (int32_t v = 0; v < m.numVertices(); ++v) {
    std::vector<int32_t> expected;
    for (int32_t f = 0; f < m.numFaces(); ++f)
      if (T[3 * f] == v || T[3 * f + 1] == v || T[3 * f + 2] == v) expected.push_back(f);
    EXPECT_EQ(
        std::vector<int32_t>(round.faces.begin() + round.start[v], round.faces.begin() + round.start[v + 1]),
        expected)
        << v;
  }
  const std::vector<double> n = pageFaceNormals(computeMeshGeometry(m, t));
  for (int32_t f = 0; f + 1 < m.numFaces(); ++f) {
    Eigen::Vector3d p[3];
    facePositions(m, f, p);
    const Eigen::Vector3d cross = twiceAreaNormal(p), unit(n[3 * f], n[3 * f + 1], n[3 * f + 2]);
    EXPECT_NEAR(unit.norm(), 1, 1e-15);
    EXPECT_NEAR(unit.dot(cross), cross.norm(), 1e-12 * cross.norm());
  }
  const size_t last = 3 * static_cast<size_t>(m.numFaces() - 1);
  EXPECT_EQ(std::vector<double>(n.begin() + last, n.end()), (std::vector<double>{0, 0, 1}));
}

TEST(MeshChecks, NamesTheFirstOffendingElement) {
  SurfaceMesh m = flatGrid(2);
  m.triangles[5] = 42;
  EXPECT_NE(firstFatal(m).find("face 1 refers to vertex 42"), std::string::npos) << firstFatal(m);

  m = flatGrid(2);
  m.positions[3 * 4 + 1] = std::nan("");
  EXPECT_NE(firstFatal(m).find("vertex 4 has a non-finite"), std::string::npos) << firstFatal(m);

  m = flatGrid(2);
  m.positions[3 * 1] = m.positions[0];  // vertex 1 onto vertex 0: face 0 collapses
  m.positions[3 * 1 + 1] = m.positions[1];
  EXPECT_NE(firstFatal(m).find("face 0 is degenerate"), std::string::npos) << firstFatal(m);

  m = flatGrid(2);
  m.triangles.insert(m.triangles.end(), {0, 1, 4});  // a third face on edge (0, 1)... and (1, 4), (0, 4)
  EXPECT_NE(firstFatal(m).find("non-manifold"), std::string::npos) << firstFatal(m);

  m = flatGrid(2);
  std::swap(m.triangles[0], m.triangles[1]);  // flip face 0
  EXPECT_NE(firstFatal(m).find("inconsistently oriented"), std::string::npos) << firstFatal(m);

  m = disjointUnion(icosphere(0), icosphere(0));  // two spheres glued at one vertex: a bow-tie vertex
  for (int32_t& v : m.triangles)
    if (v == 12) v = 0;
  EXPECT_NE(firstFatal(m).find("vertex 0 is non-manifold"), std::string::npos) << firstFatal(m);

  EXPECT_NE(firstFatal(SurfaceMesh{}).find("no triangles"), std::string::npos);
}

TEST(MeshChecks, MoebiusStripIsNonOrientable) {
  SurfaceMesh m;
  const int n = 12;
  for (int i = 0; i < n; ++i)
    for (int s = -1; s <= 1; s += 2) {
      const double a = 2 * M_PI * i / n, w = 0.3 * s;
      m.positions.insert(m.positions.end(), {(2 + w * std::cos(a / 2)) * std::cos(a),
                                             (2 + w * std::cos(a / 2)) * std::sin(a), w * std::sin(a / 2)});
    }
  for (int i = 0; i < n; ++i) {
    const int a0 = 2 * i, a1 = 2 * i + 1;
    int b0 = 2 * ((i + 1) % n), b1 = b0 + 1;
    if (i == n - 1) std::swap(b0, b1);  // the half twist
    m.triangles.insert(m.triangles.end(), {a0, b0, b1, a0, b1, a1});
  }
  EXPECT_NE(firstFatal(m).find("non-orientable"), std::string::npos) << firstFatal(m);
}

TEST(MeshInfo, ReportsCountsAndProblems) {
  const nlohmann::json info = meshInfoJson(disjointUnion(torus(8, 6, 2, 0.7), flatAnnulus(2, 10, 1, 2)));
  EXPECT_EQ(info["components"], 2);
  EXPECT_EQ(info["genus"], 1);
  EXPECT_EQ(info["boundaryLoops"], 2);
  EXPECT_EQ(info["firstBettiNumber"], 3);
  EXPECT_TRUE(info["problems"].empty());
  EXPECT_EQ(info["perComponent"].size(), 2u);
  SurfaceMesh unused = flatGrid(2);
  unused.positions.insert(unused.positions.end(), {5, 5, 5});
  const nlohmann::json withNote = meshInfoJson(unused);
  EXPECT_TRUE(withNote["usable"].get<bool>());
  ASSERT_EQ(withNote["problems"].size(), 1u);
  EXPECT_NE(withNote["problems"][0].get<std::string>().find("not used"), std::string::npos);
}

// A Designer's report, made from the topology, notes and fold profile it kept, is the report of a fresh
// check.
TEST(MeshInfo, DesignerKeepsTheCheckItWasMadeWith) {
  for (SurfaceMesh mesh : {disjointUnion(torus(8, 6, 2, 0.7), flatAnnulus(2, 10, 1, 2)), flatGrid(2)}) {
    if (mesh.numFaces() < 10) mesh.positions.insert(mesh.positions.end(), {5, 5, 5});  // an unused vertex
    const nlohmann::json fresh = meshInfoJson(mesh);
    ASSERT_TRUE(fresh.contains("folds"));
    const Designer d(mesh);
    EXPECT_EQ(meshInfoJson(d), fresh);
  }
}
