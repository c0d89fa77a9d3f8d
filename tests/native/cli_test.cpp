// The tvf command line, run as a user would: exit codes, messages on stderr, JSON keys on stdout.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "design/design_document.h"
#include "test_meshes.h"

namespace {

namespace fs = std::filesystem;

fs::path writeOff(const std::string& name, const tvf::SurfaceMesh& m) {
  const fs::path path = fs::temp_directory_path() / (std::to_string(getpid()) + "_" + name);
  std::ofstream out(path);
  out << "OFF\n" << m.numVertices() << " " << m.numFaces() << " 0\n";
  out.precision(17);
  for (int v = 0; v < m.numVertices(); ++v)
    out << m.positions[3 * v] << " " << m.positions[3 * v + 1] << " " << m.positions[3 * v + 2] << "\n";
  for (int f = 0; f < m.numFaces(); ++f)
    out << "3 " << m.triangles[3 * f] << " " << m.triangles[3 * f + 1] << " " << m.triangles[3 * f + 2]
        << "\n";
  return path;
}

fs::path writeText(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / (std::to_string(getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(Cli, InfoReportsTopology) {
  const CliRun r = runTvf("info " + writeOff("cli_torus.off", tvf::testing::torus(12, 8, 2, 0.7)).string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  for (const char* key : {"vertices", "edges", "faces", "components", "boundaryLoops", "eulerCharacteristic",
                          "genus", "problems"})
    EXPECT_TRUE(info.contains(key)) << key;
  EXPECT_EQ(info["genus"], 1);
  EXPECT_EQ(info["edges"], 288);
  EXPECT_TRUE(info["problems"].empty());
}

TEST(Cli, InfoListsProblemsOfAnUnusableMesh) {
  tvf::SurfaceMesh m = tvf::testing::flatGrid(2);
  std::swap(m.triangles[0], m.triangles[1]);
  const CliRun r = runTvf("info " + writeOff("cli_flipped.off", m).string());
  ASSERT_EQ(r.exitCode, 0);
  EXPECT_NE(nlohmann::json::parse(r.out)["problems"].dump().find("inconsistently oriented"),
            std::string::npos);
  const CliRun d = runTvf("design " + writeOff("cli_flipped.off", m).string() + " " +
                          writeText("cli_empty_design.json", "{}").string());
  EXPECT_EQ(d.exitCode, 2);
  EXPECT_NE(d.err.find("inconsistently oriented"), std::string::npos) << d.err;
}

TEST(Cli, DesignWritesTheFieldDocument) {
  const fs::path mesh = writeOff("cli_sphere.off", tvf::icosphere(2));
  const fs::path design = writeText("cli_design.json", R"({"boundary": "free", "gamma": 0, "constraints": [
      {"type": "source", "vertex": 0, "strength": 1}, {"type": "sink", "vertex": 3, "strength": 1}]})");
  const fs::path out = fs::temp_directory_path() / (std::to_string(getpid()) + "_cli_field.json");
  const CliRun r = runTvf("design " + mesh.string() + " " + design.string() + " -o " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(out);
  const auto field = nlohmann::json::parse(in);
  EXPECT_EQ(field["edges"].size(), field["oneForm"].size());
  EXPECT_EQ(field["faceVectors"].size(), 320u);
  EXPECT_EQ(field["vertexVectors"].size(), 162u);
  EXPECT_EQ(field["faceVectors"][0].size(), 3u);
  ASSERT_EQ(field["singularities"].size(), 2u);
  EXPECT_EQ(field["singularities"][0]["index"], 1.0);
  for (const char* key :
       {"factorMs", "solveMs", "nnzPerRowM", "nnzPerRowL", "kernelHandling", "positiveAreaFallbackVertices"})
    EXPECT_TRUE(field["stats"].contains(key)) << key;
}

TEST(Cli, BadInputExitsTwoWithAReason) {
  EXPECT_EQ(runTvf("info /nonexistent/mesh.off").exitCode, 2);
  EXPECT_NE(runTvf("info /nonexistent/mesh.off").err.find("mesh.off"), std::string::npos);
  EXPECT_EQ(runTvf("info " + writeText("cli_garbage.glb", "not a glb at all").string()).exitCode, 2);
  EXPECT_EQ(
      runTvf("info " + writeText("cli_nofaces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n").string()).exitCode,
      2);
  const fs::path mesh = writeOff("cli_sphere.off", tvf::icosphere(1));
  const CliRun badJson =
      runTvf("design " + mesh.string() + " " + writeText("cli_bad.json", "{ nope").string());
  EXPECT_EQ(badJson.exitCode, 2);
  EXPECT_NE(badJson.err.find("not valid JSON"), std::string::npos) << badJson.err;
  const CliRun badFace = runTvf(
      "design " + mesh.string() + " " +
      writeText("cli_badface.json", R"({"constraints": [{"type": "vortex", "face": 9999}]})").string());
  EXPECT_EQ(badFace.exitCode, 2);
  EXPECT_NE(badFace.err.find("face 9999"), std::string::npos) << badFace.err;
  EXPECT_EQ(runTvf("frobnicate x").exitCode, 2);
}

TEST(Cli, BenchPrintsTheTableKeys) {
  const fs::path mesh = writeOff("cli_bench.off", tvf::testing::torus(40, 20, 2, 0.7));
  const CliRun r = runTvf("bench " + mesh.string() + " --repeat 2 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto b = nlohmann::json::parse(r.out);
  for (const char* key : {"edges", "nnzPerRowM", "nnzPerRowL", "analyzeMs", "factorMs", "solveMs", "updateMs",
                          "strokeUpdateSolveMs", "reconstructMs"})
    EXPECT_TRUE(b.contains(key)) << key;
  EXPECT_EQ(b["edges"], 2400);
  EXPECT_GT(b["strokeUpdateSolveMs"].get<double>(), 0.0);
  EXPECT_EQ(b["ordering"], "metis");  // the default, as in the browser build
  // Plain CHOLMOD beside it, on the same matrix: the scale for the solve and the update.
  EXPECT_GT(b["plainAmdSolveMs"].get<double>(), 0.0);
  EXPECT_GT(b["plainAmdUpdateMs"].get<double>(), 0.0);
  EXPECT_GT(b["steadyUpdateMs"].get<double>(), 0.0);
  EXPECT_GT(b["plainAmdFactorNonzeros"].get<double>(), 0.0);
}

// With threads, the bench checks the factorization on them against the serial one through the session's
// field (the same bit for bit), beside the serial field with the other ordering (the system's own
// sensitivity to the order of sums).
TEST(Cli, BenchOnTwoThreadsChecksTheFieldAgainstOneThreads) {
  const fs::path mesh = writeOff("cli_bench_threads.off", tvf::icosphere(5));
  const CliRun r = runTvf("bench " + mesh.string() + " --repeat 1 --threads 2 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto b = nlohmann::json::parse(r.out);
  EXPECT_NE(b["factorKind"].get<std::string>().find("LL' on 2 threads"), std::string::npos)
      << b["factorKind"];
  EXPECT_EQ(b["parallelFieldDifference"].get<double>(), 0.0);
  EXPECT_LT(b["orderingFieldDifference"].get<double>(), 1e-12);
  EXPECT_FALSE(runTvf("bench " + mesh.string() + " --repeat 1 --threads 1 --json")
                   .out.find("parallelFieldDifference") != std::string::npos);
}

// --scaling (scripts/bench-cores.sh): the table's timings alone, without the parts that refactor (the
// singularity edits, plain CHOLMOD's baseline, the threads' field check).
TEST(Cli, BenchScalingTimesTheTableAlone) {
  const fs::path mesh = writeOff("cli_bench_scaling.off", tvf::icosphere(5));
  const CliRun r = runTvf("bench " + mesh.string() + " --repeat 1 --threads 2 --scaling --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto b = nlohmann::json::parse(r.out);
  EXPECT_TRUE(b["scaling"].get<bool>());
  for (const char* key :
       {"analyzeMs", "factorMs", "solveMs", "updateMs", "strokeUpdateSolveMs", "steadyUpdateMs"})
    EXPECT_GT(b[key].get<double>(), 0.0) << key;
  for (const char* key : {"plainAmdSolveMs", "parallelFieldDifference"}) EXPECT_FALSE(b.contains(key)) << key;
  EXPECT_TRUE(b["singularityPlaceMs"].is_null() || b["singularityPlaceMs"].get<double>() == 0.0);
}

TEST(Cli, BenchCompareReportsBothOrderings) {
  const fs::path mesh = writeOff("cli_bench_compare.off", tvf::testing::torus(40, 20, 2, 0.7));
  const CliRun r = runTvf("bench " + mesh.string() + " --repeat 1 --compare");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto b = nlohmann::json::parse(r.out);
  EXPECT_EQ(b["edges"], 2400);
  for (const char* ordering : {"metis", "amd"}) {
    ASSERT_TRUE(b.contains(ordering)) << ordering;
    EXPECT_EQ(b[ordering]["ordering"], ordering);
    EXPECT_EQ(b[ordering]["strokeEdges"], 50);
    for (const char* key : {"analyzeMs", "strokeUpdateMs", "strokeRowsMs", "strokeRhsMs", "strokeSolveMs"})
      EXPECT_TRUE(b[ordering].contains(key)) << ordering << " " << key;
  }
}

TEST(Cli, DesignForAnotherMeshIsRefusedUnlessOverridden) {
  const fs::path sphere = writeOff("cli_fp_sphere.off", tvf::icosphere(2));
  const fs::path torus = writeOff("cli_fp_torus.off", tvf::testing::torus(12, 8, 2, 0.7));
  // A design saved against the sphere: what `tvf design` reads back from its own fingerprint.
  tvf::Designer d(tvf::icosphere(2));
  d.addVortex(3, 1.0);
  const fs::path design = writeText("cli_fp_design.json", tvf::designDocument(d).dump());
  EXPECT_EQ(runTvf("design " + sphere.string() + " " + design.string()).exitCode, 0);
  const CliRun refused = runTvf("design " + torus.string() + " " + design.string());
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_TRUE(refused.out.empty());
  EXPECT_NE(refused.err.find("another mesh"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--ignore-fingerprint"), std::string::npos) << refused.err;
  const CliRun forced = runTvf("design " + torus.string() + " " + design.string() + " --ignore-fingerprint");
  EXPECT_EQ(forced.exitCode, 0) << forced.err;
  const CliRun malformed =
      runTvf("design " + sphere.string() + " " + writeText("cli_foo.json", R"({"foo": 1})").string());
  EXPECT_EQ(malformed.exitCode, 2);
  EXPECT_NE(malformed.err.find("unknown key \"foo\""), std::string::npos) << malformed.err;
}

TEST(Cli, QuadWritesTheQuadMeshAsObjAndItsStatistics) {
  const fs::path mesh = writeOff("cli_quad_torus.off", tvf::testing::torus(48, 16, 1.0, 0.35));
  const fs::path design =
      writeText("cli_quad_design.json", R"({"symmetry": 4, "exactSingularities": true, "constraints": []})");
  const fs::path out = fs::temp_directory_path() / (std::to_string(getpid()) + "_cli_quad.obj");
  const CliRun r = runTvf("quad " + mesh.string() + " " + design.string() + " -o " + out.string() +
                          " --edge-length 0.1 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto stats = nlohmann::json::parse(r.out);
  EXPECT_EQ(stats["irregularVertices"], 0);
  EXPECT_EQ(stats["eulerCharacteristic"], 0);
  EXPECT_EQ(stats["quads"], stats["faces"]);
  // The OBJ holds the mesh the statistics describe: its vertices, and its faces as quads.
  std::ifstream in(out);
  std::string line;
  int vertices = 0, faces = 0, quads = 0;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) ++vertices;
    if (line.rfind("f ", 0) == 0) {
      ++faces;
      quads += std::count(line.begin(), line.end(), ' ') == 4;
    }
  }
  EXPECT_EQ(vertices, stats["vertices"]);
  EXPECT_EQ(faces, stats["faces"]);
  EXPECT_EQ(quads, faces);
  fs::remove(out);

  const fs::path vector = writeText("cli_quad_vector.json", R"({"constraints": []})");
  const CliRun refused = runTvf("quad " + mesh.string() + " " + vector.string() + " -o " + out.string());
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_NE(refused.err.find("Quad meshes need a cross field"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(out));
}
