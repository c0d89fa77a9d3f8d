// SPDX-License-Identifier: GPL-2.0-or-later
#include "direction/stripe_texture.h"

#include <algorithm>
#include <cmath>

#include "common/input_error.h"

namespace tvf {
namespace {

double familyPhase(const StripePattern& p, int32_t numFaces, int family, int32_t f, const double b[3]) {
  const size_t slot = static_cast<size_t>(family) * numFaces + f;
  double phase = 0;
  for (int k = 0; k < 3; ++k) phase += b[k] * p.cornerPhase[3 * slot + k];
  const int n = p.branchIndex[slot];
  return n ? phase + n * stripeAngle(b[0], b[1], b[2]) : phase;
}

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

}  // namespace

double stripeValue(const StripePattern& p, int32_t numFaces, int32_t f, const double b[3]) {
  if (p.families == 1) return 0.5 + 0.5 * std::cos(familyPhase(p, numFaces, 0, f, b));
  // Grid lines: each family's stripes narrowed to lines at its phase's multiples of 2 pi, the darker wins.
  double value = 1;
  for (int family = 0; family < p.families; ++family) {
    const double c = 0.5 + 0.5 * std::cos(familyPhase(p, numFaces, family, f, b));
    value = std::min(value, 1 - std::pow(c, 8));
  }
  return value;
}

std::vector<uint8_t> stripeTextureRgba(const SurfaceMesh& mesh, const StripePattern& pattern,
                                       const std::vector<float>& cornerUVs, int size, int gutterTexels,
                                       const StripeColours& colours) {
  const int32_t nF = mesh.numFaces();
  if (size < 1 || size > 8192) throw InputError("stripe texture: the size must be in [1, 8192]");
  if (cornerUVs.size() != 6 * static_cast<size_t>(nF))
    throw InputError("stripe texture: expected 6 UV coordinates per face");
  if (pattern.cornerPhase.size() != 3 * static_cast<size_t>(nF) * pattern.families)
    throw InputError("stripe texture: the pattern is of another mesh");
  std::vector<uint8_t> rgba(4 * static_cast<size_t>(size) * size, 0);
  for (int32_t f = 0; f < nF; ++f) {
    double u[3], v[3];
    for (int k = 0; k < 3; ++k)
      u[k] = cornerUVs[6 * f + 2 * k] * size, v[k] = cornerUVs[6 * f + 2 * k + 1] * size;
    const double det = (u[1] - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (v[1] - v[0]);
    if (!(std::abs(det) > 1e-12)) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({u[0], u[1], u[2]}) - 0.5)));
    const int x1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({u[0], u[1], u[2]}) - 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({v[0], v[1], v[2]}) - 0.5)));
    const int y1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({v[0], v[1], v[2]}) - 0.5)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        double b[3];
        b[1] = ((px - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (py - v[0])) / det;
        b[2] = ((u[1] - u[0]) * (py - v[0]) - (px - u[0]) * (v[1] - v[0])) / det;
        b[0] = 1 - b[1] - b[2];
        constexpr double kSlack = -1e-9;
        if (b[0] < kSlack || b[1] < kSlack || b[2] < kSlack) continue;
        uint8_t* out = &rgba[4 * (static_cast<size_t>(y) * size + x)];
        if (out[3]) continue;  // the first face to cover a texel keeps it
        const double t = std::clamp(stripeValue(pattern, nF, f, b), 0.0, 1.0);
        for (int c = 0; c < 3; ++c)
          out[c] =
              static_cast<uint8_t>(std::lround(colours.dark[c] + t * (colours.light[c] - colours.dark[c])));
        out[3] = 255;
      }
  }
  dilate(rgba, size, gutterTexels);
  return rgba;
}

}  // namespace tvf
