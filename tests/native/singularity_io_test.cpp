// Prescribed singularities and sharp features in files: the design format's "singularities", "featureAngle"
// and "featureEdges" (round trip, and the four refusals that leave the design as it was), Directional's .sing
// (read and written), QuadWild's .rosy and .sharp (written, read back here by parsers written from the
// formats' readers: vcglib's Load4ROSY, QuadWild's LoadSharpFeatures), and the CLI that writes and reads
// them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <tuple>

#include "cli_run.h"
#include "design/design_document.h"
#include "design/designer.h"
#include "io/rosy_file.h"
#include "io/sharp_file.h"
#include "io/sing_file.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

namespace fs = std::filesystem;
using Pair = std::array<int32_t, 2>;

// The surface of a cube of side k split into unit squares (two triangles each), outward oriented, welded:
// 12 k edges on the cube's edges (dihedral 90 degrees, convex), every other edge flat.
SurfaceMesh subdividedCube(int k) {
  SurfaceMesh m;
  std::map<std::tuple<int, int, int>, int32_t> index;
  const auto vertex = [&](const Eigen::Vector3i& p) {
    const auto key = std::make_tuple(p.x(), p.y(), p.z());
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    const int32_t v = m.numVertices();
    m.positions.insert(m.positions.end(), {double(p.x()), double(p.y()), double(p.z())});
    index.emplace(key, v);
    return v;
  };
  const Eigen::Vector3i X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1), O(0, 0, 0);
  // (origin, u, v) with u x v the outward normal.
  const Eigen::Vector3i sides[6][3] = {{k * Z, X, Y}, {O, Y, X},     {k * X, Y, Z},
                                       {O, Z, Y},     {k * Y, Z, X}, {O, X, Z}};
  for (const auto& s : sides)
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) {
        const int32_t a = vertex(s[0] + i * s[1] + j * s[2]), b = vertex(s[0] + (i + 1) * s[1] + j * s[2]),
                      c = vertex(s[0] + (i + 1) * s[1] + (j + 1) * s[2]),
                      d = vertex(s[0] + i * s[1] + (j + 1) * s[2]);
        m.triangles.insert(m.triangles.end(), {a, b, c, a, c, d});
      }
  return m;
}

// A square sheet folded along its middle line x = 1/2 by 90 degrees: a valley (concave seen from the side
// the normals face) for +1, a ridge (convex) for -1.
SurfaceMesh foldedSheet(int n, double sign) {
  SurfaceMesh m = flatGrid(n, 1.0);
  for (int v = 0; v < m.numVertices(); ++v)
    m.positions[3 * v + 2] = sign * std::abs(m.positions[3 * v] - 0.5);
  return m;
}

Eigen::Vector3d position(const SurfaceMesh& m, int32_t v) {
  return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
}

Eigen::Vector3d unitNormal(const SurfaceMesh& m, int32_t f) {
  const int32_t* t = &m.triangles[3 * f];
  return (position(m, t[1]) - position(m, t[0])).cross(position(m, t[2]) - position(m, t[0])).normalized();
}

Eigen::Vector3d centroid(const SurfaceMesh& m, int32_t f) {
  const int32_t* t = &m.triangles[3 * f];
  return (position(m, t[0]) + position(m, t[1]) + position(m, t[2])) / 3;
}

Pair sorted(int32_t a, int32_t b) {
  return {std::min(a, b), std::max(a, b)};
}

// Interior edges (as sorted vertex pairs) with the two faces on them, found from the triangles alone.
std::map<Pair, std::vector<int32_t>> edgeFacesOf(const SurfaceMesh& m) {
  std::map<Pair, std::vector<int32_t>> faces;
  for (int32_t f = 0; f < m.numFaces(); ++f)
    for (int c = 0; c < 3; ++c)
      faces[sorted(m.triangles[3 * f + c], m.triangles[3 * f + (c + 1) % 3])].push_back(f);
  return faces;
}

// Edges whose faces' normals differ by more than `degrees`, computed here from positions.
std::set<Pair> creases(const SurfaceMesh& m, double degrees) {
  std::set<Pair> out;
  for (const auto& [pair, faces] : edgeFacesOf(m)) {
    if (faces.size() != 2) continue;
    const double cosine = unitNormal(m, faces[0]).dot(unitNormal(m, faces[1]));
    if (std::acos(std::clamp(cosine, -1.0, 1.0)) > degrees * M_PI / 180) out.insert(pair);
  }
  return out;
}

// QuadWild's .sharp as its LoadSharpFeatures reads it: a count, then "type,face,corner" lines.
struct SharpEntry {
  int type;
  int32_t face, corner;
};
std::vector<SharpEntry> parseSharp(const std::string& text) {
  std::vector<SharpEntry> entries;
  int count = -1;
  const char* p = text.c_str();
  int used = 0;
  EXPECT_EQ(std::sscanf(p, "%d%n", &count, &used), 1);
  p += used;
  for (int k = 0; k < count; ++k) {
    SharpEntry e{};
    EXPECT_EQ(std::sscanf(p, " %d,%d,%d%n", &e.type, &e.face, &e.corner, &used), 3) << "entry " << k;
    p += used;
    entries.push_back(e);
  }
  int trailing = 0;
  EXPECT_NE(std::sscanf(p, " %d", &trailing), 1) << "more entries than the count";
  return entries;
}

// The refusal names the problem and the designer keeps its design and its field, bit for bit.
void expectRefused(Designer& d, const nlohmann::json& doc, const std::string& needle) {
  const nlohmann::json before = designDocument(d);
  d.solve();
  const std::vector<double> field = d.faceVectors();
  try {
    applyDesignDocument(d, doc);
    ADD_FAILURE() << "accepted: " << doc.dump();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
  EXPECT_EQ(designDocument(d), before);
  d.solve();
  EXPECT_EQ(d.faceVectors(), field);
}

std::vector<std::pair<int32_t, double>> prescribedOf(const Designer& d) {
  std::vector<std::pair<int32_t, double>> out;
  for (const ConstraintSpec& s : d.constraints())
    if (s.kind == ConstraintKind::Singularity) out.push_back({s.element, s.value});
  return out;
}

}  // namespace

TEST(SingularityDesignFile, SingularitiesAndFeaturesRoundTrip) {
  const SurfaceMesh cube = subdividedCube(3);
  Designer d(cube);
  d.setSymmetry(4);
  // Two vertices inside two faces of the cube (no boundary): (1, 1, 3) and (2, 2, 0).
  const auto vertexAt = [&](double x, double y, double z) {
    for (int32_t v = 0; v < cube.numVertices(); ++v)
      if (position(cube, v) == Eigen::Vector3d(x, y, z)) return v;
    return -1;
  };
  const int32_t a = vertexAt(1, 1, 3), b = vertexAt(2, 2, 0), c = vertexAt(1, 2, 3);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  const int32_t first = d.addSingularity(a, 0.25);
  d.addSingularity(b, -0.25);
  d.moveSingularity(first, c);  // keeps its id: still first in the file
  const double along[3] = {1, 0, 0};
  d.addVector(0, along, 1.0);
  // A flat diagonal edge added, one of the cube's creases removed.
  const Pair added{cube.triangles[0], cube.triangles[2]};
  const Pair removed = *creases(cube, 35).begin();
  d.setFeatures(35, {added}, {removed});
  const nlohmann::json doc = designDocument(d);
  ASSERT_TRUE(doc.contains("singularities"));
  EXPECT_EQ(doc["singularities"],
            nlohmann::json::parse("[{\"vertex\": " + std::to_string(c) + ", \"index\": 0.25}, {\"vertex\": " +
                                  std::to_string(b) + ", \"index\": -0.25}]"));
  for (const auto& constraint : doc["constraints"]) EXPECT_NE(constraint["type"], "singularity");
  EXPECT_EQ(doc["featureAngle"], 35.0);
  EXPECT_EQ(doc["featureEdges"]["add"], nlohmann::json::array({{added[0], added[1]}}));
  EXPECT_EQ(doc["featureEdges"]["remove"], nlohmann::json::array({{removed[0], removed[1]}}));

  Designer e(cube);
  applyDesignDocument(e, nlohmann::json::parse(doc.dump()));
  EXPECT_EQ(designDocument(e), doc);
  EXPECT_EQ(prescribedOf(e), prescribedOf(d));
  EXPECT_EQ(e.featureAngle(), 35.0);
  EXPECT_EQ(e.featureEdges(), d.featureEdges());
  // The crease set in use: every crease of the cube but the removed one, plus the added diagonal.
  std::set<Pair> expected = creases(cube, 35);
  expected.erase(removed);
  expected.insert(sorted(added[0], added[1]));
  std::set<Pair> used;
  for (const int32_t edge : e.featureEdges())
    used.insert({e.edgeVertices()[2 * edge], e.edgeVertices()[2 * edge + 1]});
  EXPECT_EQ(used, expected);
}

TEST(SingularityDesignFile, DesignsWithoutTheNewKeysReplayAsBefore) {
  Designer d(icosphere(2));
  d.setSymmetry(2);
  const double along[3] = {0, 1, 0};
  d.addVector(3, along, 1.0);
  const nlohmann::json doc = designDocument(d);
  for (const char* key : {"singularities", "featureAngle", "featureEdges"})
    EXPECT_FALSE(doc.contains(key)) << key;
  Designer e(icosphere(2));
  e.setFeatures(10, {}, {});
  applyDesignDocument(e, doc);
  EXPECT_EQ(e.featureAngle(), 0.0);  // absent means none, whatever the designer had
  EXPECT_TRUE(e.featureEdges().empty());
  EXPECT_EQ(designDocument(e), doc);
}

TEST(SingularityDesignFile, FieldFileFlagsPrescribedSingularitiesAndListsFeatures) {
  const SurfaceMesh cube = subdividedCube(2);
  Designer d(cube);
  d.setSymmetry(4);
  applyDesignDocument(d, nlohmann::json::parse(R"({"constraints": [], "symmetry": 4, "featureAngle": 35})"));
  d.solve();
  const nlohmann::json field = fieldDocument(d);
  ASSERT_TRUE(field.contains("featureEdges"));
  std::set<Pair> listed;
  for (const auto& p : field["featureEdges"]) listed.insert(sorted(p[0], p[1]));
  EXPECT_EQ(listed, creases(cube, 35));
  EXPECT_EQ(field["stats"]["featureEdges"], static_cast<int>(listed.size()));
  for (const char* key : {"singularityMode", "eulerCharacteristic", "prescribedIndex", "freeIndex"})
    EXPECT_TRUE(field["stats"].contains(key)) << key;
  EXPECT_EQ(field["stats"]["eulerCharacteristic"], 2);

  // Eight vertices of a sphere, each +1/4: all the index the sphere needs, prescribed.
  Designer p(icosphere(2));
  p.setSymmetry(4);
  nlohmann::json design = nlohmann::json::parse(R"({"constraints": [], "symmetry": 4, "singularities": []})");
  for (int32_t v = 0; v < 8; ++v) design["singularities"].push_back({{"vertex", v * 20}, {"index", 0.25}});
  applyDesignDocument(p, design);
  p.solve();
  const nlohmann::json prescribed = fieldDocument(p);
  std::set<int32_t> flagged;
  for (const auto& s : prescribed["singularities"]) {
    ASSERT_TRUE(s.contains("prescribed"));
    if (s["prescribed"].get<bool>()) flagged.insert(s["vertex"].get<int32_t>());
  }
  std::set<int32_t> asked;
  for (const auto& s : design["singularities"]) asked.insert(s["vertex"].get<int32_t>());
  EXPECT_EQ(flagged, asked);
  EXPECT_EQ(prescribed["stats"]["prescribedIndex"], 2.0);
}

TEST(SingularityDesignFile, AVectorFieldWithSingularitiesIsWrittenAsDirections) {
  // Two +1 on a sphere: all the index it needs. The field is then a unit direction field, not a 1-form.
  Designer d(icosphere(2));
  applyDesignDocument(d, nlohmann::json::parse(R"({"constraints": [],
      "singularities": [{"vertex": 0, "index": 1}, {"vertex": 3, "index": 1}]})"));
  d.solve();
  const nlohmann::json field = fieldDocument(d);
  EXPECT_FALSE(field.contains("oneForm"));
  EXPECT_EQ(field["symmetry"], 1);
  ASSERT_EQ(field["faceDirections"].size(), static_cast<size_t>(d.mesh().numFaces()));
  std::set<std::pair<int32_t, double>> found;
  for (const auto& s : field["singularities"])
    found.insert({s["vertex"].get<int32_t>(), s["index"].get<double>()});
  EXPECT_EQ(found, (std::set<std::pair<int32_t, double>>{{0, 1.0}, {3, 1.0}}));
}

TEST(SingularityDesignFile, ExactSingularitiesRoundTripsAndIsWrittenOnlyWhenTrue) {
  // A torus needs no index (chi = 0): asked for exactly the prescribed singularities, none, its cross field
  // has none at all, where the smoothest field is free to place pairs.
  const SurfaceMesh ring = torus(30, 16, 2, 0.7);
  Designer d(ring);
  d.setSymmetry(4);
  EXPECT_FALSE(designDocument(d).contains("exactSingularities"));  // the default is not written
  d.setExactSingularities(true);
  const nlohmann::json doc = designDocument(d);
  ASSERT_TRUE(doc.contains("exactSingularities"));
  EXPECT_EQ(doc["exactSingularities"], true);

  Designer e(ring);
  applyDesignDocument(e, nlohmann::json::parse(doc.dump()));
  EXPECT_TRUE(e.exactSingularities());
  EXPECT_EQ(designDocument(e), doc);
  e.solve();
  EXPECT_TRUE(e.singularities().empty());
  EXPECT_EQ(e.stats().singularityMode, "exact");

  // Read before the singularities: a +/- pair on the torus is then all there is.
  nlohmann::json pair = doc;
  pair["singularities"] = {{{"vertex", 40}, {"index", 0.25}}, {{"vertex", 200}, {"index", -0.25}}};
  applyDesignDocument(e, pair);
  e.solve();
  std::set<std::pair<int32_t, double>> found;
  for (const Singularity& s : e.singularities()) found.insert({s.vertex, s.index});
  EXPECT_EQ(found, (std::set<std::pair<int32_t, double>>{{40, 0.25}, {200, -0.25}}));
  EXPECT_EQ(designDocument(e)["exactSingularities"], true);

  // A file without the key turns it off; a value that is not a boolean is refused and changes nothing.
  nlohmann::json without = doc;
  without.erase("exactSingularities");
  applyDesignDocument(e, without);
  EXPECT_FALSE(e.exactSingularities());
  nlohmann::json bad = doc;
  bad["exactSingularities"] = 1;
  expectRefused(e, bad, "\"exactSingularities\" must be true or false");
  EXPECT_FALSE(e.exactSingularities());
}

TEST(SingularityDesignFile, BadSingularitiesAndFeaturesAreRefusedByName) {
  // A sheet with a boundary (vertex 0 is its corner), with a design loaded from a file.
  Designer d(flatGrid(6, 1.0, true));
  const auto design = [](const std::string& extra) {
    return nlohmann::json::parse(R"({"symmetry": 4, "constraints": [)"
                                 R"({"type": "vector", "face": 2, "vector": [0, 1, 0], "weight": 1}])" +
                                 extra + "}");
  };
  const int32_t inner = 3 * 7 + 3;  // (3, 3) of the 7 x 7 vertices
  const int32_t other = 2 * 7 + 4;
  applyDesignDocument(d, design(R"(, "featureAngle": 20, "singularities": [{"vertex": )" +
                                std::to_string(other) + R"(, "index": 0.25}])"));
  expectRefused(d, design(R"(, "singularities": [{"vertex": 0, "index": 0.25}])"), "boundary");
  expectRefused(
      d, design(R"(, "singularities": [{"vertex": )" + std::to_string(inner) + R"(, "index": 0.3}])"), "1/4");
  const nlohmann::json twice =
      design(R"(, "singularities": [{"vertex": )" + std::to_string(inner) + R"(, "index": 0.25}, )" +
             R"({"vertex": )" + std::to_string(inner) + R"(, "index": -0.25}])");
  expectRefused(d, twice, "singularities[1]");  // the second entry, named by its place in the file
  expectRefused(d, twice, "vertex " + std::to_string(inner));
  expectRefused(d, design(R"(, "featureEdges": {"add": [[0, 48]]})"), "not a mesh edge");
  // Where they belong is said too.
  expectRefused(d, design(R"(, "singularities": {"vertex": 3})"), "\"singularities\" must be a list");
  expectRefused(d, design(R"(, "featureEdges": {"add": [[0, 1]], "keep": []})"), "unknown key \"keep\"");
  expectRefused(
      d,
      nlohmann::json::parse(R"({"symmetry": 4, "constraints": [{"type": "singularity", "vertex": )" +
                            std::to_string(inner) + R"(, "index": 0.25}]})"),
      "\"singularities\" list");
}

TEST(SingFile, WrittenThenReadGivesTheSameSet) {
  const std::vector<Singularity> set = {{12, 0.25}, {40, -0.25}, {7, 0.5}, {301, -1.0}, {2, 1.25}};
  const std::string text = writeSingFile(4, set);
  // Directional's write_singularities: "N count", then "vertex k" with index k / N.
  EXPECT_EQ(text, "4 5\n12 1\n40 -1\n7 2\n301 -4\n2 5\n");
  const SingFile back = readSingFile(text);
  EXPECT_EQ(back.symmetry, 4);
  ASSERT_EQ(back.singularities.size(), set.size());
  for (size_t k = 0; k < set.size(); ++k) {
    EXPECT_EQ(back.singularities[k].vertex, set[k].vertex);
    EXPECT_EQ(back.singularities[k].index, set[k].index);
    EXPECT_TRUE(back.singularities[k].prescribed);
  }
  // A line field's, with Directional's tutorial spacing (blank lines, tabs) read alike.
  const SingFile line = readSingFile("2\t2\n\n5 1\n  9 -1\n");
  ASSERT_EQ(line.singularities.size(), 2u);
  EXPECT_EQ(line.singularities[1].vertex, 9);
  EXPECT_EQ(line.singularities[1].index, -0.5);
}

TEST(SingFile, BadFilesAreRefusedWithTheLine) {
  const auto refused = [](const std::string& text, const std::string& needle) {
    try {
      readSingFile(text);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  refused("", "empty");
  refused("four 2\n", "\"N count\"");
  refused("4 2\n1 1\n", "announces 2");
  refused("4 1\n1 1\n2 1\n", "line 3: more entries");
  refused("4 1\n1 0.5\n", "line 2: an entry must be two integers");
  refused("4 1\n-3 1\n", "no vertex -3");
  refused("4 1\n3 0\n", "index 0");
  EXPECT_THROW(writeSingFile(4, {{3, 0.3}}), InputError);
  EXPECT_THROW(writeSingFile(4, {{3, 0.0}}), InputError);
}

TEST(RosyFile, ACrossFieldIsWrittenFaceByFace) {
  Designer d(icosphere(2));
  d.setSymmetry(4);
  const double along[3] = {1, 0.3, 0};
  d.addVector(7, along, 1.0);
  d.solve();
  const std::string text = writeRosyFile(d.faceVectors(), 4);
  // vcglib's Load4ROSY: the face count, the symmetry 4, then x y z per face.
  std::istringstream in(text);
  int faces = 0, symmetry = 0;
  ASSERT_TRUE(in >> faces >> symmetry);
  EXPECT_EQ(faces, d.mesh().numFaces());
  EXPECT_EQ(symmetry, 4);
  for (int f = 0; f < faces; ++f) {
    double x[3];
    ASSERT_TRUE(in >> x[0] >> x[1] >> x[2]) << "face " << f;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(x[i], d.faceVectors()[3 * f + i], 1e-8) << "face " << f;
    const Eigen::Vector3d n = unitNormal(d.mesh(), f);
    EXPECT_NEAR(Eigen::Vector3d(x[0], x[1], x[2]).norm(), 1.0, 1e-8);
    EXPECT_NEAR(Eigen::Vector3d(x[0], x[1], x[2]).dot(n), 0.0, 1e-8);  // in the face's plane
  }
  std::string rest;
  EXPECT_FALSE(in >> rest) << "more than one line per face";
  EXPECT_THROW(writeRosyFile(d.faceVectors(), 2), InputError);
}

TEST(SharpFile, CubeCreasesAreWrittenOncePerFaceSideAsConvex) {
  const SurfaceMesh cube = subdividedCube(3);
  Designer d(cube);
  d.setFeatures(35, {}, {});
  const std::vector<SharpEntry> entries =
      parseSharp(writeSharpFile(d.topology(), d.geometry(), cube.positions, d.featureEdges()));
  const std::set<Pair> expected = creases(cube, 35);
  ASSERT_EQ(expected.size(), 36u);  // 12 cube edges of 3 segments
  ASSERT_EQ(entries.size(), 2 * expected.size());
  std::map<Pair, int> sides;
  for (const SharpEntry& e : entries) {
    ASSERT_TRUE(e.face >= 0 && e.face < cube.numFaces() && e.corner >= 0 && e.corner < 3);
    EXPECT_EQ(e.type, 1);
    ++sides[sorted(cube.triangles[3 * e.face + e.corner], cube.triangles[3 * e.face + (e.corner + 1) % 3])];
  }
  std::set<Pair> written;
  for (const auto& [pair, count] : sides) {
    EXPECT_EQ(count, 2);
    written.insert(pair);
  }
  EXPECT_EQ(written, expected);
}

TEST(SharpFile, FoldsAreConcaveOrConvexAndTheBorderIsWritten) {
  for (const double sign : {1.0, -1.0}) {
    const SurfaceMesh sheet = foldedSheet(4, sign);
    Designer d(sheet);
    d.setFeatures(35, {}, {});
    const std::vector<SharpEntry> entries =
        parseSharp(writeSharpFile(d.topology(), d.geometry(), sheet.positions, d.featureEdges()));
    const auto faces = edgeFacesOf(sheet);
    const std::set<Pair> fold = creases(sheet, 35);
    ASSERT_EQ(fold.size(), 4u);
    size_t border = 0;
    for (const auto& [pair, list] : faces) border += list.size() == 1;
    ASSERT_EQ(entries.size(), 2 * fold.size() + border);
    for (const SharpEntry& e : entries) {
      const Pair pair =
          sorted(sheet.triangles[3 * e.face + e.corner], sheet.triangles[3 * e.face + (e.corner + 1) % 3]);
      const std::vector<int32_t>& two = faces.at(pair);
      if (two.size() == 1) {
        EXPECT_EQ(e.type, 1) << "the border is written as QuadWild marks it: convex";
        continue;
      }
      ASSERT_TRUE(fold.count(pair));
      // Concave where the other face rises to the side this face's normal points to.
      const int32_t other = two[0] == e.face ? two[1] : two[0];
      const Eigen::Vector3d midpoint = (position(sheet, pair[0]) + position(sheet, pair[1])) / 2;
      const bool concave = (centroid(sheet, other) - midpoint).dot(unitNormal(sheet, e.face)) > 0;
      EXPECT_EQ(e.type, concave ? 0 : 1);
      EXPECT_EQ(concave, sign > 0) << "a valley is concave, a ridge convex";
    }
  }
}

#ifdef TVF_CLI_PATH
namespace {

fs::path tempPath(const std::string& name) {
  return fs::temp_directory_path() / ("tvf_sing_" + std::to_string(getpid()) + "_" + name);
}

fs::path writeTemp(const std::string& name, const std::string& text) {
  const fs::path path = tempPath(name);
  std::ofstream(path) << text;
  return path;
}

fs::path writeMesh(const std::string& name, const SurfaceMesh& m) {
  return writeTemp(name, offText(m));
}

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST(SingularityCli, DesignHonoursSingularitiesAndASingFile) {
  const SurfaceMesh cube = subdividedCube(3);
  const fs::path mesh = writeMesh("cube.off", cube);
  const fs::path design = writeTemp("design.json", R"({"symmetry": 4, "constraints": [],
                         "singularities": [{"vertex": 20, "index": 0.25}]})");
  const fs::path out = tempPath("field.json");
  const CliRun r = runTvf("design " + mesh.string() + " " + design.string() + " -o " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto field = nlohmann::json::parse(readText(out));
  EXPECT_TRUE(field["featureEdges"].empty());
  bool found = false;
  for (const auto& s : field["singularities"])
    if (s["vertex"] == 20) found = s["prescribed"] == true && s["index"] == 0.25;
  EXPECT_TRUE(found) << field["singularities"].dump();

  // Directional's .sing into a design that names no symmetry: N and the indices come from the file.
  const fs::path sing = writeTemp("in.sing", "4 2\n20 1\n41 -1\n");
  const fs::path plain = writeTemp("plain.json", R"({"constraints": []})");
  const CliRun s = runTvf("design " + mesh.string() + " " + plain.string() + " --sing " + sing.string() +
                          " -o " + out.string());
  ASSERT_EQ(s.exitCode, 0) << s.err;
  const auto fromSing = nlohmann::json::parse(readText(out));
  EXPECT_EQ(fromSing["symmetry"], 4);
  std::map<int32_t, double> prescribed;
  for (const auto& e : fromSing["singularities"])
    if (e["prescribed"].get<bool>()) prescribed[e["vertex"].get<int32_t>()] = e["index"].get<double>();
  EXPECT_EQ(prescribed, (std::map<int32_t, double>{{20, 0.25}, {41, -0.25}}));

  // Refused by name, exit status 2, nothing on stdout.
  const CliRun twice = runTvf("design " + mesh.string() + " " + design.string() + " --sing " +
                              writeTemp("twice.sing", "4 1\n20 -1\n").string());
  EXPECT_EQ(twice.exitCode, 2);
  EXPECT_TRUE(twice.out.empty());
  EXPECT_NE(twice.err.find("singularities[1]"), std::string::npos) << twice.err;
  EXPECT_NE(twice.err.find("vertex 20"), std::string::npos) << twice.err;
  const CliRun bad = runTvf("design " + mesh.string() + " " + plain.string() + " --sing " +
                            writeTemp("bad.sing", "4 1\n20 x\n").string());
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("line 2"), std::string::npos) << bad.err;
}

TEST(SingularityCli, ExportWritesSingRosyAndSharp) {
  const SurfaceMesh cube = subdividedCube(2);
  const fs::path mesh = writeMesh("export_cube.off", cube);
  const fs::path design =
      writeTemp("export.json", R"({"symmetry": 4, "constraints": [], "featureAngle": 35})");
  const fs::path sing = tempPath("out.sing"), rosy = tempPath("out.rosy"), sharp = tempPath("out.sharp"),
                 field = tempPath("export_field.json");
  const CliRun r = runTvf("export " + mesh.string() + " " + design.string() + " --sing " + sing.string() +
                          " --rosy " + rosy.string() + " --sharp " + sharp.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_EQ(runTvf("design " + mesh.string() + " " + design.string() + " -o " + field.string()).exitCode, 0);
  const auto solved = nlohmann::json::parse(readText(field));
  std::set<Pair> listed;
  for (const auto& p : solved["featureEdges"]) listed.insert({p[0].get<int32_t>(), p[1].get<int32_t>()});
  EXPECT_EQ(listed, creases(cube, 35));
  // .sing: the field's singularities, k / N.
  std::istringstream singText(readText(sing));
  int n = 0, count = 0;
  ASSERT_TRUE(singText >> n >> count);
  EXPECT_EQ(n, 4);
  ASSERT_EQ(count, static_cast<int>(solved["singularities"].size()));
  std::map<int32_t, double> written, found;
  for (int k = 0; k < count; ++k) {
    int32_t v = 0, numerator = 0;
    ASSERT_TRUE(singText >> v >> numerator);
    written[v] = static_cast<double>(numerator) / n;
  }
  for (const auto& s : solved["singularities"])
    found[s["vertex"].get<int32_t>()] = std::round(4 * s["index"].get<double>()) / 4;
  EXPECT_EQ(written, found);
  // .rosy: one direction per face, the field's.
  std::istringstream rosyText(readText(rosy));
  int faces = 0, symmetry = 0;
  ASSERT_TRUE(rosyText >> faces >> symmetry);
  EXPECT_EQ(faces, cube.numFaces());
  EXPECT_EQ(symmetry, 4);
  for (int f = 0; f < faces; ++f)
    for (int i = 0; i < 3; ++i) {
      double x = 0;
      ASSERT_TRUE(rosyText >> x);
      EXPECT_NEAR(x, solved["faceDirections"][f][i].get<double>(), 1e-8);
    }
  // .sharp: both sides of each crease.
  EXPECT_EQ(parseSharp(readText(sharp)).size(), 2 * creases(cube, 35).size());
  // A line field has no .rosy.
  const CliRun line = runTvf("export " + mesh.string() + " " +
                             writeTemp("line.json", R"({"symmetry": 2, "constraints": []})").string() +
                             " --rosy " + rosy.string());
  EXPECT_EQ(line.exitCode, 2);
  EXPECT_NE(line.err.find("symmetry 4"), std::string::npos) << line.err;
}

TEST(SingularityCli, BenchReportsSingularityEdits) {
  const fs::path mesh = writeMesh("bench_torus.off", torus(30, 16, 2, 0.7));
  const CliRun r = runTvf("bench " + mesh.string() + " --repeat 2 --symmetry 4 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto b = nlohmann::json::parse(r.out);
  for (const char* key : {"singularityEditMs", "singularityPlaceMs", "singularityMoveMs"}) {
    ASSERT_TRUE(b.contains(key)) << key;
    EXPECT_GT(b[key].get<double>(), 0.0) << key;
  }
  EXPECT_GE(b["singularityEditMs"].get<double>(),
            std::min(b["singularityPlaceMs"].get<double>(), b["singularityMoveMs"].get<double>()));
  EXPECT_TRUE(b.contains("singularityFactorizations"));
  EXPECT_TRUE(b.contains("singularityFreeMoveMs"));
  // A torus needs no index (chi = 0): the pair alone is all there is, and the field has exactly it.
  EXPECT_EQ(b["singularityMode"], "exact");
}
#endif
