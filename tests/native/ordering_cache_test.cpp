// The fill-reducing ordering kept beyond the system that computed it (solver/factored_system.h KeptOrdering,
// io/ordering_file.h, the CLI's --ordering-cache): adopted by a fresh designer on the same mesh it skips the
// ordering and gives the same field; a stale, foreign or damaged one is detected and ignored.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_run.h"
#include "design/designer.h"
#include "io/ordering_file.h"
#include "test_fields.h"
#include "test_meshes.h"

namespace tvf {
namespace {

namespace fs = std::filesystem;
using testing::designEveryKind;
using testing::offText;
using testing::relativeDifference;
using testing::torus;

TEST(KeptOrdering, AdoptedOnTheSameMeshSkipsTheOrderingAndGivesTheSameField) {
  const SurfaceMesh m = torus(40, 20, 2, 0.7);
  Designer first(m);
  designEveryKind(first);
  EXPECT_FALSE(first.stats().analysisReused);
  const KeptOrdering kept = first.fieldOrdering();
  ASSERT_EQ(kept.perm.size(), static_cast<size_t>(first.topology().numEdges));
  EXPECT_TRUE(kept.dissection);  // the mesh's nested dissection ordered it

  Designer second(m);
  ASSERT_TRUE(second.adoptFieldOrdering(kept));
  designEveryKind(second);
  EXPECT_TRUE(second.stats().analysisReused);
  EXPECT_EQ(second.stats().factorKind, first.stats().factorKind);
  EXPECT_LT(relativeDifference(second.oneForm(), first.oneForm()), 1e-12);
}

TEST(KeptOrdering, OneOfAnotherPatternKindOrShapeIsIgnored) {
  const SurfaceMesh m = torus(40, 20, 2, 0.7);
  Designer first(m);
  designEveryKind(first);
  KeptOrdering kept = first.fieldOrdering();

  // Another pattern (gamma > 0 widens the stencil): adopted, then found stale at the factorization.
  Designer widened(m), fresh(m);
  widened.setGamma(0.01);
  fresh.setGamma(0.01);
  ASSERT_TRUE(widened.adoptFieldOrdering(kept));
  designEveryKind(widened);
  designEveryKind(fresh);
  EXPECT_FALSE(widened.stats().analysisReused);
  EXPECT_LT(relativeDifference(widened.oneForm(), fresh.oneForm()), 1e-12);

  // The other ordering kind, or not a permutation: refused outright.
  Designer amd(m);
  amd.setMetisOrdering(false);
  EXPECT_FALSE(amd.adoptFieldOrdering(kept));
  KeptOrdering twice = kept;
  twice.perm[1] = twice.perm[0];
  Designer other(m);
  EXPECT_FALSE(other.adoptFieldOrdering(twice));
  twice.perm = {0, 1, 2};
  // A permutation of another size, claiming the same pattern (a damaged record): stale at factorization.
  EXPECT_TRUE(other.adoptFieldOrdering(twice));
  designEveryKind(other);
  EXPECT_FALSE(other.stats().analysisReused);
  EXPECT_LT(relativeDifference(other.oneForm(), first.oneForm()), 1e-12);
}

TEST(OrderingFile, RoundTripsAndRefusesStaleForeignOrDamagedFiles) {
  KeptOrdering k;
  k.perm = {3, 0, 2, 1, 4};
  k.pattern = 0x0123456789abcdefull;
  k.ordering = FillOrdering::Metis;
  k.dissection = true;
  const std::vector<uint8_t> bytes = orderingFileBytes(42, k);
  const OrderingFile back = readOrderingFile(bytes, 42);
  ASSERT_TRUE(back.ignored.empty()) << back.ignored;
  EXPECT_EQ(back.kept.perm, k.perm);
  EXPECT_EQ(back.kept.pattern, k.pattern);
  EXPECT_EQ(back.kept.ordering, k.ordering);
  EXPECT_EQ(back.kept.dissection, k.dissection);

  EXPECT_EQ(readOrderingFile(bytes, 43).ignored, "the ordering of another mesh");
  std::vector<uint8_t> flipped = bytes;
  flipped[50] ^= 1;
  EXPECT_EQ(readOrderingFile(flipped, 42).ignored, "an ordering file whose checksum does not match");
  const std::vector<uint8_t> cut(bytes.begin(), bytes.end() - 3);
  EXPECT_EQ(readOrderingFile(cut, 42).ignored, "an ordering file cut short");
  std::vector<uint8_t> version = bytes;
  version[8] = 9;
  EXPECT_EQ(readOrderingFile(version, 42).ignored, "an ordering file of another version");
  EXPECT_EQ(readOrderingFile({'O', 'F', 'F'}, 42).ignored, "not an ordering file");
}

#ifdef TVF_CLI_PATH
TEST(OrderingCacheCli, TheSecondRunOfAMeshReusesTheOrderingAndWritesTheSameField) {
  const fs::path dir = fs::temp_directory_path() / ("tvf_ordering_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const SurfaceMesh m = torus(40, 20, 2, 0.7);
  std::ofstream(dir / "torus.off") << offText(m);
  std::ofstream(dir / "design.json")
      << R"({"constraints": [{"type": "source", "vertex": 3, "strength": 1}]})";
  const std::string args = "design " + (dir / "torus.off").string() + " " + (dir / "design.json").string() +
                           " --ignore-fingerprint --ordering-cache " + (dir / "cache").string();
  const CliRun a = runTvf(args), b = runTvf(args);
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const auto fa = nlohmann::json::parse(a.out), fb = nlohmann::json::parse(b.out);
  EXPECT_FALSE(fa["stats"]["analysisReused"].get<bool>());
  EXPECT_TRUE(fb["stats"]["analysisReused"].get<bool>());
  EXPECT_EQ(fa["oneForm"].size(), fb["oneForm"].size());
  EXPECT_LT(
      relativeDifference(fa["oneForm"].get<std::vector<double>>(), fb["oneForm"].get<std::vector<double>>()),
      1e-12);
  // A damaged cache file is named on stderr and ignored: the ordering is computed again, and rewritten.
  const fs::path file = fs::directory_iterator(dir / "cache")->path();
  { std::fstream(file, std::ios::in | std::ios::out | std::ios::binary).seekp(60).put('\x7f'); }
  const CliRun c = runTvf(args);
  ASSERT_EQ(c.exitCode, 0) << c.err;
  EXPECT_NE(c.err.find("checksum"), std::string::npos) << c.err;
  EXPECT_FALSE(nlohmann::json::parse(c.out)["stats"]["analysisReused"].get<bool>());
  EXPECT_TRUE(nlohmann::json::parse(runTvf(args).out)["stats"]["analysisReused"].get<bool>());
  fs::remove_all(dir);
}
#endif

}  // namespace
}  // namespace tvf
