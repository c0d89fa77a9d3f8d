// The texture atlas (core/texture/texture_atlas): generated charts checked with a rasterizer of the test's
// own (flips, overlaps, gutters between charts, texel density, coverage) and the usable-TEXCOORD_0 decision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "test_meshes.h"
#include "texture/texture_atlas.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

double uvArea(const std::vector<float>& uv, int32_t f) {
  const float* t = &uv[6 * static_cast<size_t>(f)];
  return 0.5 *
         ((double(t[2]) - t[0]) * (double(t[5]) - t[1]) - (double(t[4]) - t[0]) * (double(t[3]) - t[1]));
}

double surfaceArea(const SurfaceMesh& m, int32_t f) {
  double p[3][3];
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) p[k][c] = m.positions[3 * m.triangles[3 * f + k] + c];
  const double a[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
  const double b[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
  const double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// Per texel centre of an n x n grid: the chart of the face strictly containing it (barycentric coordinates
// all above eps), -1 if none, -2 if faces of two charts or two faces' interiors contain it.
struct Raster {
  std::vector<int32_t> chart;
  int overlaps = 0;
};

Raster rasterize(const TextureAtlas& atlas, int n) {
  Raster r{std::vector<int32_t>(static_cast<size_t>(n) * n, -1), 0};
  std::vector<int32_t> face(r.chart.size(), -1);
  const int32_t nF = static_cast<int32_t>(atlas.faceChart.size());
  for (int32_t f = 0; f < nF; ++f) {
    if (atlas.faceChart[f] < 0) continue;
    const float* t = &atlas.cornerUVs[6 * static_cast<size_t>(f)];
    const double ax = t[0] * n, ay = t[1] * n, bx = t[2] * n, by = t[3] * n, cx = t[4] * n, cy = t[5] * n;
    const double det = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
    if (det == 0) continue;
    const int x0 = std::max(0, int(std::floor(std::min({ax, bx, cx})))),
              x1 = std::min(n - 1, int(std::ceil(std::max({ax, bx, cx}))));
    const int y0 = std::max(0, int(std::floor(std::min({ay, by, cy})))),
              y1 = std::min(n - 1, int(std::ceil(std::max({ay, by, cy}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        const double l1 = ((px - ax) * (cy - ay) - (cx - ax) * (py - ay)) / det;
        const double l2 = ((bx - ax) * (py - ay) - (px - ax) * (by - ay)) / det;
        const double l0 = 1 - l1 - l2;
        constexpr double eps = 1e-6;
        if (l0 <= eps || l1 <= eps || l2 <= eps) continue;
        const size_t k = static_cast<size_t>(y) * n + x;
        if (face[k] >= 0) {
          ++r.overlaps;
          r.chart[k] = -2;
        } else {
          face[k] = f;
          r.chart[k] = atlas.faceChart[f];
        }
      }
  }
  return r;
}

// Every texel of one chart is more than 2 * gutter texels (Chebyshev) from every texel of another chart.
int gutterViolations(const Raster& r, int n, int gutter) {
  int bad = 0;
  const int reach = 2 * gutter;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int32_t c = r.chart[static_cast<size_t>(y) * n + x];
      if (c < 0) continue;
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= n || yy >= n) continue;
          const int32_t o = r.chart[static_cast<size_t>(yy) * n + xx];
          if (o >= 0 && o != c) ++bad;
        }
    }
  return bad;
}

// Area-weighted quantile of the per-face texel density sqrt(UV area / surface area), over the median.
std::vector<double> densityQuantiles(const SurfaceMesh& m, const TextureAtlas& atlas,
                                     std::vector<double> qs) {
  std::vector<std::pair<double, double>> d;
  double total = 0;
  for (int32_t f = 0; f < m.numFaces(); ++f) {
    const double a = surfaceArea(m, f);
    d.push_back({std::sqrt(std::abs(uvArea(atlas.cornerUVs, f)) / a), a});
    total += a;
  }
  std::sort(d.begin(), d.end());
  auto at = [&](double q) {
    double acc = 0;
    for (const auto& [v, w] : d)
      if ((acc += w) >= q * total) return v;
    return d.back().first;
  };
  const double median = at(0.5);
  for (double& q : qs) q = at(q) / median;
  return qs;
}

// Length of the edges between faces of two charts over the length of all edges, from an edge map of the
// test's own.
double seamShare(const SurfaceMesh& m, const std::vector<int32_t>& faceChart) {
  std::map<std::pair<int32_t, int32_t>, std::vector<int32_t>> faces;
  for (int32_t f = 0; f < m.numFaces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = m.triangles[3 * f + k], b = m.triangles[3 * f + (k + 1) % 3];
      faces[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  double seam = 0, total = 0;
  for (const auto& [e, fs] : faces) {
    double d2 = 0;
    for (int c = 0; c < 3; ++c)
      d2 += std::pow(m.positions[3 * e.first + c] - m.positions[3 * e.second + c], 2);
    total += std::sqrt(d2);
    if (fs.size() == 2 && faceChart[fs[0]] != faceChart[fs[1]]) seam += std::sqrt(d2);
  }
  return seam / total;
}

// The largest area-weighted 95th / 5th percentile texel density ratio within one chart: what the generator
// bounds (1.8) for every chart, flattened or kept on a split chart's map.
double largestChartDensitySpread(const SurfaceMesh& m, const TextureAtlas& atlas) {
  std::map<int32_t, std::vector<std::pair<double, double>>> perChart;
  for (int32_t f = 0; f < m.numFaces(); ++f) {
    const double a = surfaceArea(m, f);
    perChart[atlas.faceChart[f]].push_back({std::sqrt(std::abs(uvArea(atlas.cornerUVs, f)) / a), a});
  }
  double largest = 1;
  for (auto& [chart, d] : perChart) {
    std::sort(d.begin(), d.end());
    double total = 0;
    for (const auto& [v, w] : d) total += w;
    auto at = [&](double q) {
      double acc = 0;
      for (const auto& [v, w] : d)
        if ((acc += w) >= q * total) return v;
      return d.back().first;
    };
    if (d.size() > 1) largest = std::max(largest, at(0.95) / at(0.05));
  }
  return largest;
}

void expectValidAtlas(const SurfaceMesh& mesh, const TextureAtlas& atlas, double minCoverage) {
  const int n = atlas.resolution;
  ASSERT_EQ(atlas.cornerUVs.size(), 6u * mesh.numFaces());
  ASSERT_EQ(atlas.faceChart.size(), size_t(mesh.numFaces()));
  for (float u : atlas.cornerUVs) {
    ASSERT_GE(u, 0.0f);
    ASSERT_LE(u, 1.0f);
  }
  // Flip-free: every face keeps the orientation of its surface winding.
  int flipped = 0;
  for (int32_t f = 0; f < mesh.numFaces(); ++f) {
    ASSERT_GE(atlas.faceChart[f], 0) << "face " << f;
    flipped += !(uvArea(atlas.cornerUVs, f) > 0);
  }
  EXPECT_EQ(flipped, 0);
  const Raster r = rasterize(atlas, n);
  EXPECT_EQ(r.overlaps, 0);
  EXPECT_EQ(gutterViolations(r, n, atlas.gutter), 0);
  size_t covered = 0;
  for (int32_t c : r.chart) covered += c >= 0;
  const double coverage = double(covered) / r.chart.size();
  EXPECT_GE(coverage, minCoverage);
  EXPECT_NEAR(coverage, atlas.measures.coverage, 0.01);
  const std::vector<double> q = densityQuantiles(mesh, atlas, {0.05, 0.95});
  EXPECT_GT(q[0], 0.7);
  EXPECT_LT(q[1], 1.4);
  EXPECT_LE(largestChartDensitySpread(mesh, atlas), 1.8 * (1 + 1e-4));
  EXPECT_EQ(atlas.measures.flippedFaces, 0);
  EXPECT_EQ(atlas.measures.overlap, 0.0);
  const double seams = seamShare(mesh, atlas.faceChart);
  EXPECT_NEAR(atlas.measures.seamShare, seams, 1e-9);
  std::printf(
      "atlas: %d charts, coverage %.3f, used %.3f, seams %.3f, density p05 %.2f p95 %.2f, L2 stretch %.3f, "
      "%.0f "
      "ms\n",
      atlas.numCharts, coverage, atlas.used, seams, q[0], q[1], atlas.measures.stretchL2, atlas.milliseconds);
}

}  // namespace

TEST(TextureAtlas, FlatSquareIsOneSimilarChartFillingTheSquare) {
  SurfaceMesh grid = flatGrid(16, 1.0, true);
  jitterPlanar(grid, 0.2 / 16, 7);  // a fifth of a cell: no folds
  const TextureAtlas atlas = generateAtlas(grid, 128, 2);
  EXPECT_EQ(atlas.numCharts, 1);
  expectValidAtlas(grid, atlas, 0.8);
  EXPECT_EQ(atlas.measures.seamShare, 0.0);
  // A conformal map of a planar chart is a similarity: no stretch, one density.
  EXPECT_NEAR(atlas.measures.stretchL2, 1.0, 1e-3);
  EXPECT_NEAR(atlas.measures.densityMin, 1.0, 1e-3);
  EXPECT_NEAR(atlas.measures.densityMax, 1.0, 1e-3);
}

TEST(TextureAtlas, CylinderIsFlattenedWithoutStretch) {
  // A 108-degree piece of a cylinder is developable: LSCM maps it isometrically up to scale, as one chart.
  SurfaceMesh c = flatGrid(24, 1.0, true);
  for (int32_t v = 0; v < c.numVertices(); ++v) {
    const double x = c.positions[3 * v], y = c.positions[3 * v + 1];
    c.positions[3 * v] = std::cos(0.6 * M_PI * x);
    c.positions[3 * v + 1] = 2 * y;
    c.positions[3 * v + 2] = std::sin(0.6 * M_PI * x);
  }
  const TextureAtlas atlas = generateAtlas(c, 256, 2);
  EXPECT_EQ(atlas.numCharts, 1);
  expectValidAtlas(c, atlas, 0.85);
  EXPECT_LT(atlas.measures.stretchL2, 1.01);
}

TEST(TextureAtlas, SphereAndTorusChartsAreFlipFreeDisjointAndEvenlyDense) {
  for (const SurfaceMesh& mesh : {icosphere(3), torus(64, 24, 2.0, 0.7)}) {
    const TextureAtlas atlas = generateAtlas(mesh, 256, 2);
    SCOPED_TRACE(atlas.numCharts);
    expectValidAtlas(mesh, atlas, 0.5);
    EXPECT_GT(atlas.measures.seamShare, 0.0);
    EXPECT_LT(atlas.measures.seamShare, 0.15);
    EXPECT_LT(atlas.measures.stretchL2, 1.15);
  }
}

// Charts are flattened on several threads (common/thread_team.h) in rounds; the atlas must not depend on
// which thread took which chart: two runs give the same bits.
TEST(TextureAtlas, FlatteningOnThreadsIsDeterministic) {
  const SurfaceMesh two = disjointUnion(icosphere(3), torus(64, 24, 2.0, 0.7));
  const TextureAtlas a = generateAtlas(two, 512, 2), b = generateAtlas(two, 512, 2);
  EXPECT_GT(a.numCharts, 8);
  EXPECT_EQ(a.numCharts, b.numCharts);
  EXPECT_EQ(a.splits, b.splits);
  EXPECT_EQ(a.faceChart, b.faceChart);
  EXPECT_EQ(a.cornerUVs, b.cornerUVs);
}

TEST(TextureAtlas, SeveralComponentsAndGutters) {
  const SurfaceMesh two = disjointUnion(icosphere(2), torus(32, 12, 2.0, 0.7));
  for (int gutter : {0, 1, 3}) {
    const TextureAtlas atlas = generateAtlas(two, 256, gutter);
    SCOPED_TRACE(gutter);
    expectValidAtlas(two, atlas, gutter < 3 ? 0.52 : 0.46);
  }
}

// A split chart's pieces that pass on its map are kept on it (a bumpy strip: its one grown chart fails the
// density bound, and so do some of its pieces). With pieces kept, every chart still meets the generator's
// bounds: expectValidAtlas checks each chart's own density spread, flips and overlaps.
TEST(TextureAtlas, PiecesKeptOnASplitChartsMapAreValidCharts) {
  SurfaceMesh mesh = flatGrid(64, 1.0, true);
  for (int32_t v = 0; v < mesh.numVertices(); ++v) {
    double* p = &mesh.positions[3 * v];
    p[0] *= 3;
    p[2] = 0.06 * std::sin(6 * M_PI * p[0]) * std::sin(6 * M_PI * p[1]);
  }
  const TextureAtlas atlas = generateAtlas(mesh, 512, 2);
  EXPECT_GT(atlas.splits, 0);
  EXPECT_GT(atlas.keptPieces, 0);
  expectValidAtlas(mesh, atlas, 0.45);
  EXPECT_LT(atlas.measures.stretchL2, 1.05);
}

TEST(TextureAtlas, BadInputIsReported) {
  const SurfaceMesh grid = flatGrid(4);
  EXPECT_THROW(generateAtlas(grid, 8, 2), InputError);
  EXPECT_THROW(generateAtlas(grid, 256, -1), InputError);
  SurfaceMesh bad = grid;
  bad.triangles[5] = 1000;
  EXPECT_THROW(generateAtlas(bad, 256, 2), InputError);
  EXPECT_THROW(generateAtlas(SurfaceMesh{}, 256, 2), InputError);
}

TEST(TextureAtlas, UsableTexcoordDecision) {
  const SurfaceMesh grid = flatGrid(8);
  std::vector<float> uv(6 * grid.numFaces());
  for (int32_t f = 0; f < grid.numFaces(); ++f)
    for (int k = 0; k < 3; ++k) {
      uv[6 * f + 2 * k] = float(grid.positions[3 * grid.triangles[3 * f + k]]);
      uv[6 * f + 2 * k + 1] = float(grid.positions[3 * grid.triangles[3 * f + k] + 1]);
    }
  const AtlasCheck ok = checkAtlasUVs(uv, grid.numFaces());
  EXPECT_TRUE(ok.usable) << ok.reason;
  EXPECT_NEAR(ok.coverage, 1.0, 1e-9);

  std::vector<float> tiling = uv;
  for (float& x : tiling) x *= 2;
  EXPECT_FALSE(checkAtlasUVs(tiling, grid.numFaces()).usable);
  EXPECT_NE(checkAtlasUVs(tiling, grid.numFaces()).reason.find("outside"), std::string::npos);

  // Two halves of the surface stacked on the same texels (mirrored islands).
  std::vector<float> stacked = uv;
  for (size_t i = 0; i < stacked.size(); i += 2) stacked[i] = std::min(stacked[i], 1.0f - stacked[i]);
  const AtlasCheck st = checkAtlasUVs(stacked, grid.numFaces());
  EXPECT_FALSE(st.usable);
  EXPECT_NE(st.reason.find("overlap"), std::string::npos);

  std::vector<float> nan = uv;
  nan[3] = std::nanf("");
  EXPECT_FALSE(checkAtlasUVs(nan, grid.numFaces()).usable);
  EXPECT_FALSE(checkAtlasUVs({}, grid.numFaces()).usable);

  // A generated atlas passes its own check.
  const TextureAtlas gen = generateAtlas(icosphere(2), 256, 2);
  EXPECT_TRUE(checkAtlasUVs(gen.cornerUVs, icosphere(2).numFaces(), 256).usable);
}

// A bumpy grid with a non-manifold fin, a sliver and a zero-area face: a chart that fails to flatten is
// split, and shortening the split's cut can move every face back to one side. The charting must still end (it
// once retried that chart forever) with every face in some chart.
TEST(TextureAtlas, SplittingAlwaysMakesProgressOnAnOddMesh) {
  SurfaceMesh m;
  const int n = 24;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n + 0.2 / n * std::sin(i * 12.9898 + j * 78.233);
      const double y = double(j) / n + 0.2 / n * std::cos(i * 4.1 + j * 9.7);
      m.positions.insert(m.positions.end(), {x, y, 0.3 * std::sin(3 * x) * std::cos(2 * y)});
    }
  const auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const int32_t nv = m.numVertices();
  m.positions.insert(m.positions.end(), {0.5, 0.5, 1.0, 0.04, 0.0, 0.0});
  m.triangles.insert(m.triangles.end(), {0, 1, nv});      // a third face on edge (0, 1)
  m.triangles.insert(m.triangles.end(), {1, nv + 1, 2});  // a sliver
  m.triangles.insert(m.triangles.end(), {3, 4, 4});       // zero area
  const TextureAtlas atlas = generateAtlas(m, 256, 2);
  ASSERT_EQ(atlas.cornerUVs.size(), 6 * static_cast<size_t>(m.numFaces()));
  for (double uv : atlas.cornerUVs) EXPECT_TRUE(std::isfinite(uv));
}
