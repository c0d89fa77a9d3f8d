// SPDX-License-Identifier: GPL-2.0-or-later
#include "direction/stripe_texture.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angles.h"
#include "common/input_error.h"

namespace tvf {
namespace {

// Fills uncovered texels from covered 8-neighbours, one ring per pass.
void dilate(std::vector<uint8_t>& rgba, int size, int passes) {
  std::vector<uint8_t> next;
  for (int pass = 0; pass < passes; ++pass) {
    next = rgba;
    bool changed = false;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        uint8_t* out = &next[4 * (static_cast<size_t>(y) * size + x)];
        if (out[3]) continue;
        int sum[3] = {0, 0, 0}, count = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int u = x + dx, v = y + dy;
            if (u < 0 || v < 0 || u >= size || v >= size) continue;
            const uint8_t* in = &rgba[4 * (static_cast<size_t>(v) * size + u)];
            if (!in[3]) continue;
            for (int c = 0; c < 3; ++c) sum[c] += in[c];
            ++count;
          }
        if (!count) continue;
        for (int c = 0; c < 3; ++c) out[c] = static_cast<uint8_t>(sum[c] / count);
        out[3] = 255;
        changed = true;
      }
    rgba.swap(next);
    if (!changed) break;
  }
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}
double fract(double x) {
  return x - std::floor(x);
}
// Distance to the nearest whole number.
double offWhole(double x) {
  return std::abs(fract(x + 0.5) - 0.5);
}
// 0 on a line of half-width `half` round whole x, 1 off it, over a footprint w.
double line(double x, double half, double w) {
  return smoothstep(half - w, half + w, offWhole(x));
}

// A texel's profile is filtered over this many texels' phase change: a renderer samples the baked texture
// bilinearly, a texel's reach each side, and a thin line filtered over one texel alone steps along the texel
// grid. Grid lines (the smoothest cross fields, 2048 texels square, scripts/stripe-quality.mjs --symmetry 4),
// each family of the pattern away from singularities: bunny00 1.80 / 1.62 degrees off the field filtered over
// two texels, 1.50 / 1.34 over three; homer 1.30 / 1.06 -> 0.63 / 0.53; lion-head 0.86 / 0.78 -> 0.58 / 0.53;
// camel 1.30 / 1.26 -> 1.03 / 0.96 (one texel: bunny00's worse and better family per face 3.30 / 1.70, two
// 2.44 / 0.98). The lines stay sharp (bunny00: 43 texels a period, a line 5 wide). The one-family stripes,
// softer already, read the same (bunny00 0.76, homer 0.75).
constexpr double kTexelsFiltered = 3;

// The phase's change per texel of face f's UV triangle (u, v in texels), in periods: the footprint the
// profile is filtered over (the linear part's gradient; a branch face's turn about its centre adds little).
double texelFootprint(const StripePattern& p, int32_t nF, int32_t f, const double u[3], const double v[3],
                      double det) {
  double w = 0;
  for (int family = 0; family < p.families; ++family) {
    const float* g = &p.cornerPhase[3 * (static_cast<size_t>(family) * nF + f)];
    const double dx = ((g[1] - g[0]) * (v[2] - v[0]) - (g[2] - g[0]) * (v[1] - v[0])) / det;
    const double dy = ((g[2] - g[0]) * (u[1] - u[0]) - (g[1] - g[0]) * (u[2] - u[0])) / det;
    w = std::max(w, 0.5 * (std::abs(dx) + std::abs(dy)) / kTwoPi);
  }
  return w;
}

// Face f's UV triangle in texels (u, v), and twice its signed area there.
double texelTriangle(const std::vector<float>& cornerUVs, int32_t f, int size, double u[3], double v[3]) {
  for (int k = 0; k < 3; ++k)
    u[k] = cornerUVs[6 * f + 2 * k] * size, v[k] = cornerUVs[6 * f + 2 * k + 1] * size;
  return (u[1] - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (v[1] - v[0]);
}

// Each vertex's footprint, the largest of its faces': a line drawn either side of a chart seam, where the two
// charts' texel densities differ, is then filtered alike at the same point of the surface, and within a chart
// the filter changes smoothly from face to face.
std::vector<double> vertexFootprints(const SurfaceMesh& mesh, const StripePattern& p,
                                     const std::vector<float>& cornerUVs, int size) {
  const int32_t nF = mesh.numFaces();
  std::vector<double> out(mesh.numVertices(), 0.0);
  for (int32_t f = 0; f < nF; ++f) {
    double u[3], v[3];
    const double det = texelTriangle(cornerUVs, f, size, u, v);
    if (!(std::abs(det) > 1e-12)) continue;
    const double w = texelFootprint(p, nF, f, u, v, det);
    for (int k = 0; k < 3; ++k) {
      double& at = out[mesh.triangles[3 * f + k]];
      at = std::max(at, w);
    }
  }
  return out;
}

// A chart's texels just outside its triangles, which a renderer's bilinear sample at the chart's edge mixes
// in, carry the pattern continued from the nearest face rather than an average of their neighbours: grid
// lines crossing a seam then read alike from both charts.
constexpr double kExtrapolatedTexels = 1.5;

struct Bake {
  const SurfaceMesh& mesh;
  const StripePattern& pattern;
  const std::vector<float>& cornerUVs;
  int size;
  const StripeColours& colours;
  StripeProfile profile;
  double lineWidth;
  std::vector<double> footprint;  // per vertex
};

// The texture, and each texel's distance outside the face that painted it (0 inside, +inf where unpainted).
struct BakedTexels {
  explicit BakedTexels(int size)
      : rgba(4 * static_cast<size_t>(size) * size, 0),
        outside(static_cast<size_t>(size) * size, std::numeric_limits<float>::infinity()) {}
  std::vector<uint8_t> rgba;
  std::vector<float> outside;
};

// Paints face f's texels: with margin 0 those whose centre it covers (the first face to cover one keeps it),
// else those within `margin` texels outside it that no face covers, each from the nearest such face.
void paintFace(const Bake& bake, int32_t f, double margin, BakedTexels& texels) {
  const int32_t nF = bake.mesh.numFaces();
  const int size = bake.size;
  double u[3], v[3], w[3];
  const double det = texelTriangle(bake.cornerUVs, f, size, u, v);
  if (!(std::abs(det) > 1e-12)) return;
  for (int k = 0; k < 3; ++k) w[k] = kTexelsFiltered * bake.footprint[bake.mesh.triangles[3 * f + k]];
  // Texels per unit of barycentric coordinate k across the opposite edge: a coordinate's distance in texels.
  double height[3];
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    height[k] = std::abs(det) / std::max(std::hypot(u[j] - u[i], v[j] - v[i]), 1e-12);
  }
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({u[0], u[1], u[2]}) - 0.5 - margin)));
  const int x1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({u[0], u[1], u[2]}) - 0.5 + margin)));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({v[0], v[1], v[2]}) - 0.5 - margin)));
  const int y1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({v[0], v[1], v[2]}) - 0.5 + margin)));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      double b[3];
      b[1] = ((px - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (py - v[0])) / det;
      b[2] = ((u[1] - u[0]) * (py - v[0]) - (px - u[0]) * (v[1] - v[0])) / det;
      b[0] = 1 - b[1] - b[2];
      double out = 0;
      for (int k = 0; k < 3; ++k) out = std::max(out, -b[k] * height[k]);
      const size_t texel = static_cast<size_t>(y) * size + x;
      constexpr double kSlack = 1e-9;
      if (margin == 0 ? (out > kSlack || texels.outside[texel] == 0)
                      : (out > margin || out >= texels.outside[texel]))
        continue;
      texels.outside[texel] = margin == 0 ? 0.0f : static_cast<float>(out);
      const double first = stripePhase(bake.pattern, nF, 0, f, b) / kTwoPi;
      const double second = bake.pattern.families > 1 ? stripePhase(bake.pattern, nF, 1, f, b) / kTwoPi : 0.0;
      const double width = b[0] * w[0] + b[1] * w[1] + b[2] * w[2];
      const double t =
          std::clamp(stripeProfileValue(bake.profile, first, second, width, bake.lineWidth), 0.0, 1.0);
      uint8_t* rgba = &texels.rgba[4 * texel];
      for (int c = 0; c < 3; ++c)
        rgba[c] = static_cast<uint8_t>(
            std::lround(bake.colours.dark[c] + t * (bake.colours.light[c] - bake.colours.dark[c])));
      rgba[3] = 255;
    }
}

}  // namespace

StripeProfile stripeProfileNamed(const std::string& name) {
  for (const StripeProfile p : {StripeProfile::Stripes, StripeProfile::WoodRings, StripeProfile::GridLines,
                                StripeProfile::Bricks, StripeProfile::Weave})
    if (name == stripeProfileName(p)) return p;
  throw InputError("stripe profile '" + name + "': expected stripes, wood, grid, bricks or weave");
}

const char* stripeProfileName(StripeProfile profile) {
  switch (profile) {
    case StripeProfile::WoodRings:
      return "wood";
    case StripeProfile::GridLines:
      return "grid";
    case StripeProfile::Bricks:
      return "bricks";
    case StripeProfile::Weave:
      return "weave";
    default:
      return "stripes";
  }
}

bool stripeProfileHasTwoFamilies(StripeProfile profile) {
  return profile == StripeProfile::GridLines || profile == StripeProfile::Bricks ||
         profile == StripeProfile::Weave;
}

double stripePatternFrequencyFactor(StripeProfile profile) {
  return profile == StripeProfile::Bricks || profile == StripeProfile::Weave ? 0.5 : 1.0;
}

double stripeDefaultWidth(StripeProfile profile) {
  switch (profile) {
    case StripeProfile::Stripes:
      return 0.5;
    case StripeProfile::WoodRings:
      return 0.7;
    case StripeProfile::GridLines:
    case StripeProfile::Bricks:
      return 0.12;
    case StripeProfile::Weave:
      return 1.0;
  }
  return 0.5;
}

double stripeProfileValue(StripeProfile profile, double x, double y, double w, double width) {
  if (!(width > 0)) width = stripeDefaultWidth(profile);
  const double half = 0.5 * std::min(width, 1.0);
  switch (profile) {
    case StripeProfile::Stripes: {
      // The edges softened over 0.4 of the narrower of band and gap (0.1 of a period at the default width),
      // or the pixel's footprint where that is wider.
      const double soft = std::max(w, 0.4 * std::min(half, 0.5 - half));
      return smoothstep(half - soft, half + soft, offWhole(x));
    }
    case StripeProfile::WoodRings: {
      const double late = 1 - smoothstep(0.0, half + w, offWhole(x));
      return 1 - 0.8 * late * late;
    }
    case StripeProfile::GridLines:
      return std::min(line(x, half, w), line(y, half, w));
    case StripeProfile::Bricks: {
      const double X = 2 * x, Y = 2 * y, row = std::floor(X + 0.5);
      const double along = 0.5 * Y + 0.5 * (row - 2 * std::floor(0.5 * row));
      return std::min(line(X + 0.5, half, 2 * w), line(along, 0.5 * half, w));
    }
    case StripeProfile::Weave: {
      const double X = 2 * x, Y = 2 * y, i = std::floor(X + 0.5), j = std::floor(Y + 0.5);
      const bool alongOnTop = (i + j) - 2 * std::floor(0.5 * (i + j)) < 0.5;
      const double d = alongOnTop ? X - i : Y - j;  // across the thread on top, in [-1/2, 1/2]
      if (std::abs(d) > half) return 0;             // the gap between threads narrower than a period
      return 0.2 + 0.8 * std::sqrt(std::max(std::cos(M_PI * d * 0.5 / half), 0.0));
    }
  }
  return 1;
}

double stripePhase(const StripePattern& p, int32_t numFaces, int family, int32_t f, const double b[3]) {
  const size_t slot = static_cast<size_t>(family) * numFaces + f;
  double phase = 0;
  for (int k = 0; k < 3; ++k) phase += b[k] * p.cornerPhase[3 * slot + k];
  const int n = p.branchIndex[slot];
  return n ? phase + n * stripeAngle(b[0], b[1], b[2]) : phase;
}

std::vector<float> stripeTexcoords(const SurfaceMesh& mesh, const MeshTopology& t, const StripePattern& p) {
  constexpr double kTolerance = 1e-2;  // periods
  const int32_t nF = mesh.numFaces();
  if (p.cornerPhase.size() != 3 * static_cast<size_t>(nF) * p.families)
    throw InputError("stripe texture coordinates: the pattern is of another mesh");
  std::vector<float> out(6 * static_cast<size_t>(nF), 0.0f);
  std::vector<double> value(3 * static_cast<size_t>(nF));
  std::vector<int32_t> queue;
  for (int family = 0; family < p.families; ++family) {
    // The phase at each corner, in periods: the linear part plus a branch face's turn there (0, 1/3, 2/3 of
    // n).
    for (int32_t f = 0; f < nF; ++f) {
      const size_t slot = static_cast<size_t>(family) * nF + f;
      for (int k = 0; k < 3; ++k)
        value[3 * f + k] = p.cornerPhase[3 * slot + k] / kTwoPi + p.branchIndex[slot] * k / 3.0;
    }
    std::vector<uint8_t> done(nF, 0);
    for (int32_t seed = 0; seed < nF; ++seed) {
      if (done[seed]) continue;
      done[seed] = 1;
      queue.assign(1, seed);
      for (size_t head = 0; head < queue.size(); ++head) {
        const int32_t f = queue[head];
        for (int c = 0; c < 3; ++c) {
          const int32_t e = t.edgeOf(f, c);
          const int32_t g = t.edgeFaces[2 * e] == f ? t.edgeFaces[2 * e + 1] : t.edgeFaces[2 * e];
          if (g < 0 || done[g]) continue;
          // The edge's two vertices as corners of f and of g.
          const int32_t a = mesh.triangles[3 * f + c], b = mesh.triangles[3 * f + (c + 1) % 3];
          int ga = -1, gb = -1;
          for (int k = 0; k < 3; ++k) {
            if (mesh.triangles[3 * g + k] == a) ga = k;
            if (mesh.triangles[3 * g + k] == b) gb = k;
          }
          if (ga < 0 || gb < 0) continue;
          const double shift = std::round(value[3 * f + c] - value[3 * g + ga]);
          if (std::abs(value[3 * f + c] - value[3 * g + ga] - shift) > kTolerance ||
              std::abs(value[3 * f + (c + 1) % 3] - value[3 * g + gb] - shift) > kTolerance)
            continue;  // a seam
          for (int k = 0; k < 3; ++k) value[3 * g + k] += shift;
          done[g] = 1;
          queue.push_back(g);
        }
      }
    }
    for (size_t i = 0; i < value.size(); ++i) out[2 * i + family] = static_cast<float>(value[i]);
  }
  return out;
}

std::vector<uint8_t> stripeTextureRgba(const SurfaceMesh& mesh, const StripePattern& pattern,
                                       const std::vector<float>& cornerUVs, int size, int gutterTexels,
                                       const StripeColours& colours, StripeProfile profile, double width) {
  const int32_t nF = mesh.numFaces();
  if (size < 1 || size > 8192) throw InputError("stripe texture: the size must be in [1, 8192]");
  if (!(width == 0 || (width > 0 && width <= 1)))
    throw InputError(
        "stripe texture: the line width must be in (0, 1] (a share of a period), or 0 for the "
        "profile's own");
  if (cornerUVs.size() != 6 * static_cast<size_t>(nF))
    throw InputError("stripe texture: expected 6 UV coordinates per face");
  if (pattern.cornerPhase.size() != 3 * static_cast<size_t>(nF) * pattern.families)
    throw InputError("stripe texture: the pattern is of another mesh");
  if (stripeProfileHasTwoFamilies(profile) && pattern.families < 2)
    throw InputError(std::string("stripe texture: the ") + stripeProfileName(profile) +
                     " profile needs two families of stripes");
  const Bake bake{mesh,    pattern, cornerUVs, size,
                  colours, profile, width,     vertexFootprints(mesh, pattern, cornerUVs, size)};
  BakedTexels texels(size);
  for (int32_t f = 0; f < nF; ++f) paintFace(bake, f, 0.0, texels);
  for (int32_t f = 0; f < nF; ++f) paintFace(bake, f, kExtrapolatedTexels, texels);
  dilate(texels.rgba, size, gutterTexels);
  return std::move(texels.rgba);
}

}  // namespace tvf
