// The fill-reducing ordering kept beyond the system that computed it (solver/factored_system.h KeptOrdering,
// io/ordering_file.h, the CLI's --ordering-cache): adopted by a fresh designer on the same mesh it skips the
// ordering and gives the same field; a stale, foreign or damaged one is detected and ignored.
#include <gtest/gtest.h>

#include <algorithm>
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
  EXPECT_TRUE(first.fieldOrderingIsNew());
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

// A mesh whose field system factors by supernodes (a small torus's is simplicial: nothing to keep).
SurfaceMesh supernodalTorus() {
  return torus(90, 45, 2, 0.7);
}

// The kept ordering of a designed model, with its symbolic factor.
KeptOrdering keptWithSymbolic(const SurfaceMesh& m, std::vector<double>& oneForm) {
  Designer first(m);
  first.keepFieldSymbolic(true);
  designEveryKind(first);
  oneForm = first.oneForm();
  return first.fieldOrdering();
}

TEST(KeptSymbolic, AdoptedWithTheOrderingSkipsTheAnalysisAndGivesTheSameField) {
  const SurfaceMesh m = supernodalTorus();
  std::vector<double> truth;
  const KeptOrdering kept = keptWithSymbolic(m, truth);
  ASSERT_FALSE(kept.symbolic.empty());
  EXPECT_EQ(kept.symbolic.super.front(), 0);
  EXPECT_EQ(static_cast<size_t>(kept.symbolic.super.back()), kept.perm.size());
  // Not asked for: none kept.
  Designer plain(m);
  designEveryKind(plain);
  EXPECT_TRUE(plain.fieldOrdering().symbolic.empty());

  Designer second(m);
  ASSERT_TRUE(second.adoptFieldOrdering(kept));
  designEveryKind(second);
  EXPECT_TRUE(second.stats().analysisReused);
  EXPECT_TRUE(second.stats().symbolicReused);
  EXPECT_EQ(second.stats().factorKind, plain.stats().factorKind);
  EXPECT_LT(relativeDifference(second.oneForm(), truth), 1e-12);
  // The same factor: its nonzeros per row as the analysis's.
  EXPECT_DOUBLE_EQ(second.stats().nnzPerRowL, plain.stats().nnzPerRowL);
  // It served that factorization alone (the design did not ask to keep one): nothing is left to hand on.
  second.keepFieldSymbolic(true);
  EXPECT_TRUE(second.fieldOrdering().symbolic.empty());
  EXPECT_FALSE(second.fieldOrderingIsNew());
}

TEST(KeptSymbolic, ItsBytesGiveItBackAndDamagedOnesNothing) {
  const SurfaceMesh m = supernodalTorus();
  std::vector<double> oneForm;
  const KeptSymbolic k = keptWithSymbolic(m, oneForm).symbolic;
  ASSERT_FALSE(k.empty());
  const std::vector<uint8_t> bytes = symbolicBytes(k);
  EXPECT_LT(bytes.size(), 4 * k.s.size());  // smaller than the rows alone
  const KeptSymbolic back = symbolicFromBytes(bytes.data(), bytes.size());
  EXPECT_EQ(back.super, k.super);
  EXPECT_EQ(back.pi, k.pi);
  EXPECT_EQ(back.s, k.s);
  EXPECT_TRUE(symbolicBytes(KeptSymbolic()).empty());
  EXPECT_TRUE(symbolicFromBytes(bytes.data(), bytes.size() - 1).empty());  // cut short
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_TRUE(symbolicFromBytes(longer.data(), longer.size()).empty());  // bytes left over
  const std::vector<uint8_t> huge = {0xff, 0xff, 0xff, 0xff, 0x7f};      // a count past 31 bits
  EXPECT_TRUE(symbolicFromBytes(huge.data(), huge.size()).empty());
  std::vector<uint8_t> zeroStep = bytes;
  // The first supernode with a row below its columns: its first step made 0 (rows must increase).
  const auto varintSize = [](uint32_t v) { return v < 0x80 ? 1u : v < 0x4000 ? 2u : v < 0x200000 ? 3u : 4u; };
  size_t at = varintSize(static_cast<uint32_t>(k.super.size() - 1));
  for (size_t t = 0; t + 1 < k.super.size(); ++t) {
    const uint32_t columns = k.super[t + 1] - k.super[t], below = k.pi[t + 1] - k.pi[t] - columns;
    at += varintSize(columns) + varintSize(below);
    if (below > 0) break;
  }
  ASSERT_NE(zeroStep[at], 0);
  zeroStep[at] = 0;
  EXPECT_TRUE(symbolicFromBytes(zeroStep.data(), zeroStep.size()).empty());
}

TEST(KeptSymbolic, OneThatDoesNotFitTheMatrixIsRefusedAndTheAnalysisRuns) {
  const SurfaceMesh m = supernodalTorus();
  std::vector<double> truth;
  const KeptOrdering kept = keptWithSymbolic(m, truth);
  ASSERT_FALSE(kept.symbolic.empty());
  const KeptSymbolic& k = kept.symbolic;
  Designer fresh(m);
  designEveryKind(fresh);
  // The first supernode with rows below its columns, and the position of its last row.
  int t = 0;
  while (k.pi[t + 1] - k.pi[t] == k.super[t + 1] - k.super[t]) ++t;
  const int last = k.pi[t + 1] - 1;
  std::vector<std::pair<const char*, KeptSymbolic>> damaged;
  KeptSymbolic d = k;
  d.s[last] = static_cast<int32_t>(kept.perm.size());  // a row out of range
  damaged.emplace_back("row out of range", d);
  d = k;
  std::swap(d.s[k.pi[t]], d.s[k.pi[t] + 1 < k.pi[t + 1] ? k.pi[t] + 1 : k.pi[t]]);
  if (d.s == k.s) d.s[k.pi[t]] = 1;
  damaged.emplace_back("columns out of order", d);
  d = k;
  d.s.erase(d.s.begin() + last);  // an entry of A (or a row the parent needs) dropped
  for (size_t u = t + 1; u < d.pi.size(); ++u) --d.pi[u];
  damaged.emplace_back("a row dropped", d);
  d = k;
  d.super.back() -= 1;
  damaged.emplace_back("columns short", d);
  d = k;
  d.pi.pop_back();
  damaged.emplace_back("pointers cut short", d);
  for (const auto& [what, symbolic] : damaged) {
    KeptOrdering bad = kept;
    bad.symbolic = symbolic;
    Designer other(m);
    ASSERT_TRUE(other.adoptFieldOrdering(bad)) << what;
    other.keepFieldSymbolic(true);
    designEveryKind(other);
    EXPECT_TRUE(other.stats().analysisReused) << what;
    EXPECT_FALSE(other.stats().symbolicReused) << what;
    // Refused before the factorization: none failed on a pattern missing fill and was tried again.
    EXPECT_EQ(other.stats().kernelHandling, fresh.stats().kernelHandling) << what;
    EXPECT_LT(relativeDifference(other.oneForm(), truth), 1e-12) << what;
    // The analysis made instead is there for the cache to store in place of the damaged one.
    EXPECT_TRUE(other.fieldOrderingIsNew()) << what;
    EXPECT_EQ(other.fieldOrdering().symbolic.s, k.s) << what;
  }
  // An ordering kept without a symbolic factor (the page's first format): the analysis made is new too; the
  // ordering alone, asked for no symbolic factor, is not.
  KeptOrdering bare = kept;
  bare.symbolic = KeptSymbolic();
  Designer keeping(m), plain(m);
  ASSERT_TRUE(keeping.adoptFieldOrdering(bare));
  ASSERT_TRUE(plain.adoptFieldOrdering(bare));
  keeping.keepFieldSymbolic(true);
  designEveryKind(keeping);
  designEveryKind(plain);
  EXPECT_TRUE(keeping.fieldOrderingIsNew());
  EXPECT_FALSE(plain.fieldOrderingIsNew());
  // A well-formed pattern that is not closed: a row below a supernode's columns dropped from its parent's
  // rows.
  int child = 0, r = 0, parent = 0;
  for (child = 0;; ++child) {
    const int below = k.pi[child] + k.super[child + 1] - k.super[child];
    if (below == k.pi[child + 1]) continue;
    r = k.s[k.pi[child + 1] - 1];
    parent =
        static_cast<int>(std::upper_bound(k.super.begin(), k.super.end(), k.s[below]) - k.super.begin()) - 1;
    if (r >= k.super[parent + 1]) break;  // r lies below the parent's columns too
  }
  d = k;
  const auto at = std::find(d.s.begin() + d.pi[parent], d.s.begin() + d.pi[parent + 1], r);
  ASSERT_NE(at, d.s.begin() + d.pi[parent + 1]);
  d.s.erase(at);
  for (size_t u = parent + 1; u < d.pi.size(); ++u) --d.pi[u];
  KeptOrdering bad = kept;
  bad.symbolic = d;
  Designer other(m);
  ASSERT_TRUE(other.adoptFieldOrdering(bad));
  designEveryKind(other);
  EXPECT_FALSE(other.stats().symbolicReused);
  EXPECT_EQ(other.stats().kernelHandling, fresh.stats().kernelHandling);
  EXPECT_LT(relativeDifference(other.oneForm(), truth), 1e-12);

  // Another pattern (gamma > 0): stale, ordering and symbolic factor both.
  Designer widened(m);
  widened.setGamma(0.01);
  ASSERT_TRUE(widened.adoptFieldOrdering(kept));
  designEveryKind(widened);
  EXPECT_FALSE(widened.stats().analysisReused);
  EXPECT_FALSE(widened.stats().symbolicReused);
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

  EXPECT_TRUE(back.kept.symbolic.empty());
  // With a symbolic factor: the same bytes back.
  std::vector<double> oneForm;
  KeptOrdering withSymbolic = keptWithSymbolic(supernodalTorus(), oneForm);
  const OrderingFile both = readOrderingFile(orderingFileBytes(42, withSymbolic), 42);
  ASSERT_TRUE(both.ignored.empty()) << both.ignored;
  EXPECT_EQ(both.kept.perm, withSymbolic.perm);
  EXPECT_EQ(both.kept.symbolic.s, withSymbolic.symbolic.s);
  EXPECT_EQ(both.kept.symbolic.pi, withSymbolic.symbolic.pi);

  EXPECT_EQ(readOrderingFile(bytes, 43).ignored, "the ordering of another mesh");
  std::vector<uint8_t> flipped = bytes;
  flipped[50] ^= 1;
  EXPECT_EQ(readOrderingFile(flipped, 42).ignored, "an ordering file whose checksum does not match");
  // A header and a checksum's room only (the permutation's and symbolic factor's sizes cannot be read).
  const std::vector<uint8_t> headerOnly(bytes.begin(), bytes.begin() + 8 + 4 + 4 + 8 + 8 + 8 + 8);
  EXPECT_EQ(readOrderingFile(headerOnly, 42).ignored, "an ordering file cut short");
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
  const SurfaceMesh m = supernodalTorus();
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
  EXPECT_TRUE(fb["stats"]["symbolicReused"].get<bool>());  // no analysis at all
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
