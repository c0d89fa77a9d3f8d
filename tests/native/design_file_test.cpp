// Design files that cannot hurt: the mesh fingerprint, schema and key checks, and a refused document leaves the
// design and its solved field exactly as they were.
#include <gtest/gtest.h>

#include <cmath>

#include "design/design_document.h"
#include "design/designer.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

// The refusal names the problem and the designer keeps its design and its one-form, bit for bit.
void expectRefused(Designer& d, const nlohmann::json& doc, const std::string& needle) {
  const nlohmann::json before = designDocument(d);
  d.solve();
  const std::vector<double> oneForm = d.oneForm();
  try {
    applyDesignDocument(d, doc);
    ADD_FAILURE() << doc.dump();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
  EXPECT_EQ(designDocument(d), before);
  d.solve();
  EXPECT_EQ(d.oneForm(), oneForm);
}

}  // namespace

TEST(DesignFile, FingerprintCountsAndHashFollowTheMesh) {
  const SurfaceMesh a = icosphere(2);
  const nlohmann::json f = meshFingerprint(a);
  EXPECT_EQ(f["vertices"], a.numVertices());
  EXPECT_EQ(f["faces"], a.numFaces());
  EXPECT_EQ(f["hash"].get<std::string>().size(), 16u);
  EXPECT_EQ(meshFingerprint(icosphere(2)), f);
  // Same counts, one vertex moved by far more than float rounding: another mesh.
  SurfaceMesh moved = a;
  moved.positions[4] += 1e-3;
  EXPECT_NE(meshFingerprint(moved)["hash"], f["hash"]);
  // Same positions, one triangle's corners rotated (same face, other first corner): another triangle list.
  SurfaceMesh rotated = a;
  std::swap(rotated.triangles[0], rotated.triangles[1]);
  std::swap(rotated.triangles[1], rotated.triangles[2]);
  EXPECT_NE(meshFingerprint(rotated)["hash"], f["hash"]);
  // A difference below float32 resolution (text round trips) keeps the fingerprint.
  SurfaceMesh jitter = a;
  jitter.positions[4] = std::nextafter(jitter.positions[4], 10.0);
  EXPECT_EQ(meshFingerprint(jitter), f);
}

TEST(DesignFile, SavedDesignsCarryTheSchemaAndFingerprint) {
  Designer d(icosphere(1));
  d.addSource(0, 1.0);
  const nlohmann::json doc = designDocument(d);
  EXPECT_EQ(doc["schema"], kDesignSchema);
  EXPECT_EQ(doc["mesh"], meshFingerprint(icosphere(1)));
  Designer e(icosphere(1));
  applyDesignDocument(e, doc);
  EXPECT_EQ(designDocument(e), doc);
}

TEST(DesignFile, ADesignForAnotherMeshIsRefusedUnlessOverridden) {
  Designer bunnyLike(icosphere(2));
  bunnyLike.addVortex(5, 1.0);
  const nlohmann::json other = designDocument(bunnyLike);
  // Same counts (an icosphere with one vertex moved): counts alone would not tell.
  SurfaceMesh moved = icosphere(2);
  moved.positions[0] *= 1.01;
  Designer d(moved);
  d.addSource(3, 1.0);
  d.addSink(40, 1.0);
  expectRefused(d, other, "another mesh");
  // Explicitly overridden, the indices are taken as they are.
  applyDesignDocument(d, other, false);
  ASSERT_EQ(d.constraints().size(), 1u);
  EXPECT_EQ(d.constraints()[0].kind, ConstraintKind::Vortex);
}

TEST(DesignFile, MalformedAndUnknownSchemaDocumentsAreRefused) {
  Designer d(icosphere(1));
  d.addSource(0, 1.0);
  d.addSink(7, 1.0);
  expectRefused(d, nlohmann::json::parse(R"({"foo": 1})"), "unknown key \"foo\"");
  expectRefused(d, nlohmann::json::parse(R"({})"), "no \"constraints\"");
  expectRefused(d, nlohmann::json::parse(R"({"schema": "tvf-design/99", "constraints": []})"), "unknown design schema");
  expectRefused(d, nlohmann::json::parse(R"({"constraints": [], "mesh": 3})"), "\"mesh\" must be");
  expectRefused(d, nlohmann::json::parse(R"([1, 2])"), "JSON object");
  // A document without schema or fingerprint (older files) still loads.
  applyDesignDocument(d, nlohmann::json::parse(R"({"constraints": [{"type": "vortex", "face": 2}]})"));
  EXPECT_EQ(d.constraints().size(), 1u);
}
