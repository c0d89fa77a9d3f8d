// Exemplar analysis for texture synthesis (core/texture/): procedural exemplars, toroidal Gaussian stack,
// appearance space (PCA), synthesis-neighbourhood space, k-coherence candidates and the GPU table layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <random>

#include "mesh/surface_mesh.h"
#include "texture/exemplar_analysis.h"
#include "texture/kd_tree.h"
#include "texture/procedural_exemplars.h"

using namespace tvf;

namespace {

double meanColour(const ExemplarImage& img, int c) {
  double s = 0;
  for (int p = 0; p < img.pixels(); ++p) s += img.rgb[3 * p + c];
  return s / img.pixels();
}

double variance(const ExemplarImage& img) {
  double v = 0;
  for (int c = 0; c < 3; ++c) {
    const double mu = meanColour(img, c);
    for (int p = 0; p < img.pixels(); ++p) v += (img.rgb[3 * p + c] - mu) * (img.rgb[3 * p + c] - mu);
  }
  return v / img.pixels();
}

// Mean absolute colour step across the column (row) boundary b -> b + 1, wrapping.
double stepAcross(const ExemplarImage& img, bool alongX, int b) {
  const int m = img.size;
  double d = 0;
  for (int a = 0; a < m; ++a) {
    const float* p = alongX ? img.at(b, a) : img.at(a, b);
    const float* q = alongX ? img.at(b + 1, a) : img.at(a, b + 1);
    for (int c = 0; c < 3; ++c) d += std::abs(p[c] - q[c]);
  }
  return d / m;
}

double distance(const RowMatrixXf& v, int a, int b) { return (v.row(a) - v.row(b)).norm(); }

const std::vector<std::string>& names() {
  static const std::vector<std::string> n = proceduralExemplarNames();
  return n;
}

}  // namespace

TEST(TextureExemplars, ProceduralAreDeterministicInRangeAndTileSeamlessly) {
  for (const std::string& name : names()) {
    SCOPED_TRACE(name);
    const ExemplarImage a = makeProceduralExemplar(name, 64, 3);
    const ExemplarImage b = makeProceduralExemplar(name, 64, 3);
    EXPECT_EQ(a.rgb, b.rgb);
    EXPECT_NE(makeProceduralExemplar(name, 64, 4).rgb, a.rgb) << "the seed changes the pattern";
    for (float v : a.rgb) ASSERT_TRUE(v >= 0 && v <= 1);
    EXPECT_GT(variance(a), 0.005) << "a pattern, not a flat colour";
    // Seamless: stepping over the wrap-around seam is like stepping over the middle column (row), which every
    // pattern's period (a divisor of size / 2) puts at the same phase.
    for (bool alongX : {true, false}) {
      const double wrap = stepAcross(a, alongX, 63), middle = stepAcross(a, alongX, 31);
      EXPECT_LT(wrap, 2.0 * middle + 0.02) << (alongX ? "x" : "y") << " seam";
    }
  }
  EXPECT_THROW(makeProceduralExemplar("plaid", 64), InputError);
  EXPECT_THROW(makeProceduralExemplar("stripes", 48), InputError);
}

TEST(TextureExemplars, RGBA8RoundTripAndValidation) {
  const ExemplarImage a = makeProceduralExemplar("scales", 32);
  const std::vector<uint8_t> bytes = exemplarToRGBA8(a);
  const ExemplarImage b = exemplarFromRGBA8(bytes.data(), 32, 32);
  for (size_t i = 0; i < a.rgb.size(); ++i) EXPECT_NEAR(a.rgb[i], b.rgb[i], 0.5 / 255 + 1e-6);
  EXPECT_THROW(exemplarFromRGBA8(bytes.data(), 32, 16), InputError);
  EXPECT_THROW(exemplarFromRGBA8(bytes.data(), 24, 24), InputError);
}

TEST(TextureStack, LevelsKeepTheMeanLoseVarianceAndWrap) {
  const ExemplarImage ex = makeProceduralExemplar("weave", 64);
  const GaussianStack stack = buildGaussianStack(ex);
  ASSERT_EQ(stack.numLevels(), 7);  // 0 .. log2(64)
  double prev = variance(ex) * 1.0000001;
  for (int s = 0; s < stack.numLevels(); ++s) {
    SCOPED_TRACE(s);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(meanColour(stack.levels[s], c), meanColour(ex, c), 1e-5);
    const double v = variance(stack.levels[s]);
    EXPECT_LE(v, prev);
    prev = v;
  }
  EXPECT_LT(variance(stack.levels.back()), 1e-3 * variance(ex)) << "the last level is nearly flat";
  // Toroidal: the stack of a shifted exemplar is the shifted stack, exactly (same sums in the same order).
  const GaussianStack shifted = buildGaussianStack(shiftedExemplar(ex, 32, 32));
  for (int s = 0; s < stack.numLevels(); ++s)
    EXPECT_EQ(shifted.levels[s].rgb, shiftedExemplar(stack.levels[s], 32, 32).rgb) << "level " << s;
}

TEST(TextureAppearance, EightDimensionsKeepNinetyPercentOfTheVariance) {
  for (const std::string& name : names()) {
    const ExemplarImage ex = makeProceduralExemplar(name, 64);
    const GaussianStack stack = buildGaussianStack(ex);
    for (int s = 0; s < stack.numLevels(); ++s) {
      const AppearanceLevel a = appearanceLevel(stack, s);
      const bool flat = variance(stack.levels[s]) < 1e-3 * variance(ex);
      std::printf("[ appearance ] %-8s level %d: 8 of 75 dims keep %.4f of the variance%s\n", name.c_str(), s,
                  a.basis.varianceKept, flat ? " (flat level, not checked)" : "");
      if (!flat) EXPECT_GE(a.basis.varianceKept, 0.90) << name << " level " << s;
      // Orthonormal axes, projections with zero mean and the eigenvalues as their variances.
      const Eigen::MatrixXf gram = a.basis.axes.transpose() * a.basis.axes;
      EXPECT_LT((gram - Eigen::MatrixXf::Identity(8, 8)).cwiseAbs().maxCoeff(), 1e-4);
      for (int d = 0; d < 8; ++d) {
        const double mean = a.vectors.col(d).cast<double>().mean();
        const double var = a.vectors.col(d).cast<double>().squaredNorm() / a.vectors.rows() - mean * mean;
        EXPECT_NEAR(mean, 0, 1e-3);
        EXPECT_NEAR(var, a.basis.eigenvalues[d], 1e-3 * a.basis.eigenvalues[0] + 1e-7);
      }
    }
  }
}

// The analysis of an exemplar moved by half its size on the torus is the same analysis moved: appearance and
// neighbourhood distances between corresponding pixel pairs agree (the PCA axes themselves may differ by sign, or
// by a rotation inside an eigenspace of equal eigenvalues, which distances do not see), and the k-coherence
// candidate sets are the moved ones.
TEST(TextureAppearance, HalfSizeShiftAnalysesIdenticallyUpToTheShift) {
  const int m = 64, half = m / 2;
  const auto moved = [&](int p) { return ((p / m + half) % m) * m + (p % m + half) % m; };
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> any(0, m * m - 1);
  for (const std::string& name : names()) {
    SCOPED_TRACE(name);
    const ExemplarImage ex = makeProceduralExemplar(name, m);
    const ExemplarAnalysis a = analyzeExemplar(ex);
    const ExemplarAnalysis b = analyzeExemplar(shiftedExemplar(ex, half, half));
    ASSERT_EQ(a.numLevels(), b.numLevels());
    for (int s = 0; s + 1 < a.numLevels(); ++s) {  // the last level is flat: all distances are rounding noise
      SCOPED_TRACE(s);
      const AnalysisLevel& la = a.levels[s];
      const AnalysisLevel& lb = b.levels[s];
      const double scaleA = std::sqrt(la.appearance.basis.eigenvalues[0]);
      const double scaleN = std::sqrt(la.neighbourhood.basis.eigenvalues[0]);
      double worstA = 0, worstN = 0;
      for (int t = 0; t < 4000; ++t) {
        const int p = any(rng), q = any(rng);
        worstA = std::max(worstA, std::abs(distance(la.appearance.vectors, p, q) -
                                           distance(lb.appearance.vectors, moved(p), moved(q))));
        worstN = std::max(worstN, std::abs(distance(la.neighbourhood.vectors, p, q) -
                                           distance(lb.neighbourhood.vectors, moved(p), moved(q))));
      }
      EXPECT_LT(worstA / scaleA, 2e-3);
      EXPECT_LT(worstN / scaleN, 2e-3);
      EXPECT_NEAR(la.appearance.basis.varianceKept, lb.appearance.basis.varianceKept, 1e-5);
      int same = 0;
      for (int p = 0; p < m * m; ++p) {
        bool all = true;
        for (int j = 0; j < la.candidates.k; ++j)
          all = all && moved(la.candidates.candidates[p * la.candidates.k + j]) ==
                           lb.candidates.candidates[moved(p) * lb.candidates.k + j];
        same += all;
      }
      // Near-ties between candidates may resolve differently in the last float digit; almost all must match.
      EXPECT_GE(same, 0.95 * m * m) << "pixels whose candidate sets are the moved originals";
    }
  }
}

// Candidates are checked where the level still resolves the patterns (spacing <= size / 16: features of the
// procedural exemplars are size / 8 to size / 4); on blurrier levels only the exclusion rule is checked.
TEST(TextureKCoherence, CandidatesAreFarNearerThanRandomPixelsAndExcludeNearSelf) {
  std::mt19937 rng(7);
  for (const std::string& name : names()) {
    const ExemplarImage ex = makeProceduralExemplar(name, 64);
    const ExemplarAnalysis an = analyzeExemplar(ex);
    const int m = an.size(), n = m * m;
    for (int s = 0; s < an.numLevels(); ++s) {
      const AnalysisLevel& L = an.levels[s];
      const int k = L.candidates.k, r = L.candidates.radius;
      ASSERT_GE(k, 2);
      double candA = 0, randA = 0, candN = 0, randN = 0;
      int separated = 0;
      std::uniform_int_distribution<int> any(0, n - 1);
      for (int u = 0; u < n; ++u) {
        for (int j = 0; j < k; ++j) {
          const int32_t c = L.candidates.candidates[u * k + j];
          ASSERT_GT(toroidalChebyshev(c, u, m), r) << "near-self candidate at level " << s;
          candA += distance(L.appearance.vectors, u, c);
          candN += distance(L.neighbourhood.vectors, u, c);
          const int v = any(rng);
          randA += distance(L.appearance.vectors, u, v);
          randN += distance(L.neighbourhood.vectors, u, v);
        }
        separated += toroidalChebyshev(L.candidates.candidates[u * k], L.candidates.candidates[u * k + 1], m) > r;
      }
      const bool resolved = L.appearance.spacing * 16 <= m;
      std::printf("[ k-coherence ] %-8s level %d (radius %d, lattice %d): candidate/random distance appearance "
                  "%.3f, neighbourhood %.3f, separated pairs %.3f%s\n",
                  name.c_str(), s, r, L.candidates.step, candA / randA, candN / randN, double(separated) / n,
                  resolved ? "" : " (blurred level: exclusion checked only)");
      if (!resolved) continue;
      EXPECT_LT(candA / randA, 0.15) << name << " level " << s;
      EXPECT_LT(candN / randN, 0.15) << name << " level " << s;
      EXPECT_GE(separated, 0.9 * n);
    }
  }
}

TEST(TextureKdTree, MatchesBruteForceWithExclusion) {
  std::mt19937 rng(11);
  std::normal_distribution<float> g;
  const int n = 3000, d = 8;
  std::vector<float> pts(n * d);
  for (float& v : pts) v = g(rng);
  const KdTree tree(pts.data(), n, d, 5);
  std::vector<std::pair<float, int32_t>> found;
  for (int q = 0; q < 200; ++q) {
    const auto skip = [&](int32_t p) { return p % 7 == q % 7; };
    tree.nearest(&pts[q * d], 6, skip, found);
    std::vector<std::pair<float, int32_t>> brute;
    for (int p = 0; p < n; ++p) {
      if (skip(p)) continue;
      float s = 0;
      for (int c = 0; c < d; ++c) s += (pts[p * d + c] - pts[q * d + c]) * (pts[p * d + c] - pts[q * d + c]);
      brute.emplace_back(s, p);
    }
    std::partial_sort(brute.begin(), brute.begin() + 6, brute.end());
    ASSERT_EQ(found.size(), 6u);
    for (int j = 0; j < 6; ++j) EXPECT_EQ(found[j].second, brute[j].second);
  }
}

TEST(TextureGpuTables, BlockProjectionReproducesTheNeighbourhoodVectors) {
  const ExemplarAnalysis an = analyzeExemplar(makeProceduralExemplar("scales", 32));
  const int m = an.size();
  for (int s : {0, 2}) {
    const GpuLevelTables g = gpuTables(an, s);
    const AnalysisLevel& L = an.levels[s];
    const int h = L.appearance.spacing;
    for (int y = 0; y < m; y += 5)
      for (int x = 0; x < m; x += 3) {
        float yv[8];
        for (int j = 0; j < 8; ++j) yv[j] = -g.projectionOffset[j];
        for (int nb = 0; nb < kNeighbourCount; ++nb) {
          const int q = ((y + kNeighbourOffsets[nb][1] * h) & (m - 1)) * m + ((x + kNeighbourOffsets[nb][0] * h) & (m - 1));
          for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 8; ++j) yv[j] += g.projection[64 * nb + 8 * i + j] * g.appearance[8 * q + i];
        }
        const int p = y * m + x;
        for (int j = 0; j < 8; ++j) EXPECT_NEAR(yv[j], g.neighbourhood[8 * p + j], 1e-3) << s << " " << p;
        const int c0 = static_cast<int>(g.candidates[4 * p + 1]) * m + static_cast<int>(g.candidates[4 * p]);
        EXPECT_EQ(c0, L.candidates.candidates[p * L.candidates.k]);
      }
  }
}

TEST(TextureAnalysis, A128ExemplarHasEightLevelsAndReportsItsTimings) {
  const ExemplarImage ex = makeProceduralExemplar("scales", 128);
  const ExemplarAnalysis an = analyzeExemplar(ex);
  const AnalysisTimings& t = an.timings;
  std::printf("[ timing ] 128^2 exemplar, %d levels: stack %.1f ms, appearance %.1f ms, neighbourhood %.1f ms, "
              "k-coherence %.1f ms, total %.1f ms\n",
              an.numLevels(), t.stackMs, t.appearanceMs, t.neighbourhoodMs, t.kCoherenceMs, t.totalMs);
  EXPECT_EQ(an.numLevels(), 8);  // timings are reported above, never asserted
}

TEST(TextureAnalysis, FlatTinyAndInvalidExemplars) {
  // A constant colour: every level flat, PCA degenerate but defined, candidates still excluded from near-self.
  ExemplarImage flat;
  flat.size = 16;
  flat.rgb.assign(3 * 16 * 16, 0.5f);
  const ExemplarAnalysis a = analyzeExemplar(flat);
  ASSERT_EQ(a.numLevels(), 5);
  for (const AnalysisLevel& L : a.levels) {
    EXPECT_DOUBLE_EQ(L.appearance.basis.varianceKept, 1.0);
    for (int u = 0; u < 256; ++u)
      for (int j = 0; j < L.candidates.k; ++j)
        EXPECT_GT(toroidalChebyshev(L.candidates.candidates[u * L.candidates.k + j], u, 16), L.candidates.radius);
    EXPECT_TRUE(L.appearance.vectors.allFinite());
    EXPECT_TRUE(L.neighbourhood.vectors.allFinite());
  }
  // The smallest procedural size analyses, and the GPU tables have the documented sizes.
  const ExemplarAnalysis tiny = analyzeExemplar(makeProceduralExemplar("weave", 16));
  const GpuLevelTables g = gpuTables(tiny, 0);
  EXPECT_EQ(g.colour.size(), 4u * 256);
  EXPECT_EQ(g.appearance.size(), 8u * 256);
  EXPECT_EQ(g.neighbourhood.size(), 8u * 256);
  EXPECT_EQ(g.candidates.size(), 4u * 256);
  EXPECT_EQ(g.projection.size(), 512u);
  EXPECT_EQ(g.projectionOffset.size(), 8u);
  EXPECT_THROW(gpuTables(tiny, tiny.numLevels()), InputError);
  // Not square / not a power of two.
  ExemplarImage bad;
  bad.size = 12;
  bad.rgb.assign(3 * 144, 0.f);
  EXPECT_THROW(analyzeExemplar(bad), InputError);
  AnalysisOptions four;
  four.appearanceDims = 4;
  EXPECT_THROW(gpuTables(analyzeExemplar(flat, four), 0), InputError);
}

// Real patterns (GIMP's tiling .pat files from Debian's gimp-data, converted by scripts/fetch-exemplars.sh into
// bench-data/exemplars/, never committed): skipped unless that folder exists (or TVF_EXEMPLAR_DIR names one).
namespace {

bool readPpm(const std::string& path, ExemplarImage& out) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  int w = 0, h = 0, maxval = 0;
  const bool header = std::fscanf(f, "P6 %d %d %d", &w, &h, &maxval) == 3 && std::fgetc(f) != EOF;
  std::vector<uint8_t> rgb(header && w > 0 && h > 0 ? 3 * static_cast<size_t>(w) * h : 0);
  const bool ok = header && maxval == 255 && w == h && !rgb.empty() && std::fread(rgb.data(), 1, rgb.size(), f) == rgb.size();
  std::fclose(f);
  if (!ok) return false;
  std::vector<uint8_t> rgba(4 * static_cast<size_t>(w) * h, 255);
  for (size_t p = 0; p < static_cast<size_t>(w) * h; ++p)
    for (int c = 0; c < 3; ++c) rgba[4 * p + c] = rgb[3 * p + c];
  out = exemplarFromRGBA8(rgba.data(), w, h);
  return true;
}

}  // namespace

TEST(TextureExemplars, RealPatternsFromGimpData) {
  const char* env = std::getenv("TVF_EXEMPLAR_DIR");
  const std::filesystem::path dir = env ? std::filesystem::path(env)
                                        : std::filesystem::path(TVF_TEST_DATA_DIR) / ".." / ".." / ".." / "bench-data" / "exemplars";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no " << dir << " (run scripts/fetch-exemplars.sh)";
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".ppm") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) GTEST_SKIP() << "no .ppm in " << dir;
  int patterns = 0, kept90 = 0, candidatesClose = 0, levels = 0;
  std::vector<double> level0;
  std::mt19937 rng(3);
  for (const auto& path : files) {
    ExemplarImage ex;
    if (!readPpm(path.string(), ex)) continue;
    if (ex.size > 64) {  // 64^2 keeps the test quick: box-filter down by whole factors
      const int f = ex.size / 64;
      ExemplarImage small;
      small.size = 64;
      small.rgb.assign(3 * 64 * 64, 0.f);
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
          for (int j = 0; j < f; ++j)
            for (int i = 0; i < f; ++i)
              for (int c = 0; c < 3; ++c) small.at(x, y)[c] += ex.at(x * f + i, y * f + j)[c] / (f * f);
      ex = small;
    }
    const ExemplarAnalysis an = analyzeExemplar(ex);
    const int m = an.size(), n = m * m;
    std::uniform_int_distribution<int> any(0, n - 1);
    std::printf("[ real ] %-14s %3d^2  variance kept by level:", path.stem().string().c_str(), m);
    for (int s = 0; s < an.numLevels() && an.levels[s].appearance.spacing * 16 <= m; ++s) {
      const AnalysisLevel& L = an.levels[s];
      double cand = 0, rnd = 0;
      for (int u = 0; u < n; u += 7)
        for (int j = 0; j < L.candidates.k; ++j) {
          cand += distance(L.appearance.vectors, u, L.candidates.candidates[u * L.candidates.k + j]);
          rnd += distance(L.appearance.vectors, u, any(rng));
        }
      std::printf(" %.3f (cand/rand %.2f)", L.appearance.basis.varianceKept, cand / rnd);
      if (s == 0) level0.push_back(L.appearance.basis.varianceKept);
      kept90 += L.appearance.basis.varianceKept >= 0.9;
      candidatesClose += cand / rnd < 0.5;
      ++levels;
    }
    std::printf("\n");
    ++patterns;
  }
  ASSERT_GT(patterns, 0);
  std::sort(level0.begin(), level0.end());
  std::printf("[ real ] %d patterns, %d levels: %d keep >= 90%% in 8 dims, median level 0 %.3f; candidates nearer than "
              "half the random distance on %d levels\n",
              patterns, levels, kept90, level0[level0.size() / 2], candidatesClose);
  EXPECT_GE(kept90, 0.8 * levels);
  EXPECT_GE(candidatesClose, 0.9 * levels);
}
