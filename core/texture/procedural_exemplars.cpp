#include "texture/procedural_exemplars.h"

#include <algorithm>
#include <cmath>

#include "mesh/surface_mesh.h"

namespace tvf {
namespace {

constexpr float kPi = 3.14159265358979f;

uint32_t hash3(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  h ^= h >> 15;
  return h;
}

float smooth(float t) { return t * t * (3 - 2 * t); }
float smoothstep(float a, float b, float x) { return smooth(std::clamp((x - a) / (b - a), 0.0f, 1.0f)); }
float fract(float x) { return x - std::floor(x); }

// A few octaves of tileable noise, in [0, 1].
float fbm(float x, float y, int size, int cellsX, int cellsY, unsigned seed, int octaves) {
  float sum = 0, amp = 1, norm = 0;
  for (int o = 0; o < octaves && cellsX <= size && cellsY <= size; ++o, cellsX *= 2, cellsY *= 2, amp *= 0.5f) {
    sum += amp * tileableNoise(x, y, size, cellsX, cellsY, seed + 101 * o);
    norm += amp;
  }
  return sum / norm;
}

void mix(float* out, const float* a, const float* b, float t) {
  for (int c = 0; c < 3; ++c) out[c] = a[c] + (b[c] - a[c]) * t;
}

// Each pattern is a colour at a continuous point of the torus [0, m)^2; the image averages 4x4 samples per pixel
// so that edges are antialiased (hard, aliased edges would put energy where no real photograph has it).
void stripes(float x, float y, int m, unsigned seed, float* p) {
  const float period = m / 4.0f;
  const float light[3] = {0.86f, 0.74f, 0.52f}, dark[3] = {0.36f, 0.19f, 0.11f};
  // Gentle waviness with whole periods across the tile (so it wraps), plus a slow noise wobble.
  const float wobble = 0.08f * period * std::sin(2 * kPi * x / m + 0.7f) +
                       0.10f * period * (fbm(x, y, m, 2, 2, seed, 2) - 0.5f);
  const float t = fract((y + wobble) / period);
  const float band = smoothstep(0.08f, 0.22f, t) - smoothstep(0.58f, 0.72f, t);
  // Grain: noise stretched along x (fibres run with the stripes).
  const float grain = fbm(x, y, m, std::max(2, m / 32), std::max(2, m / 8), seed + 7, 2) - 0.5f;
  mix(p, light, dark, band);
  for (int c = 0; c < 3; ++c) p[c] = std::clamp(p[c] * (1.0f + 0.18f * grain), 0.0f, 1.0f);
}

void scales(float x, float y, int m, unsigned seed, float* p) {
  const float w = m / 4.0f, h = m / 8.0f, radius = 0.62f * w;
  const float base[3] = {0.30f, 0.55f, 0.42f}, tip[3] = {0.70f, 0.85f, 0.55f}, rim[3] = {0.10f, 0.20f, 0.15f};
  const int rows = m / static_cast<int>(h), cols = 4;
  // Rows are drawn bottom-up: the scale of the lowest row whose disc holds the point is on top.
  float best = -1, by = 0, hue = 0;
  for (int dj = 3; dj >= -1 && best < 0; --dj) {
    const int j = static_cast<int>(std::floor(y / h)) + dj;
    const float cy = j * h;
    const float shift = (((j % 2) + 2) % 2) ? w / 2 : 0;
    for (int di = -1; di <= 1; ++di) {
      const int i = static_cast<int>(std::floor((x - shift) / w)) + di;
      const float cx = i * w + shift + w / 2;
      const float dx = x - cx, dy = y - cy;
      const float r = std::sqrt(dx * dx + dy * dy) / radius;
      if (r < 1 && dy < 0.5f * radius && (best < 0 || r < best)) {
        best = r;
        by = dy;
        hue = (hash3(((i % cols) + cols) % cols, ((j % rows) + rows) % rows, seed) & 1023) / 1023.0f;
      }
    }
  }
  if (best < 0) best = 1;
  // Light towards the free (+y) edge of each scale, a soft dark rim at its outline, a little hue per scale.
  const float along = std::clamp(0.5f + by / (2 * radius), 0.0f, 1.0f);
  mix(p, base, tip, 0.25f + 0.55f * along * (1 - 0.6f * best) + 0.15f * hue);
  mix(p, p, rim, 0.75f * smoothstep(0.62f, 1.0f, best));
}

void weave(float x, float y, int m, unsigned seed, float* p) {
  const float block = m / 4.0f, thread = block / 4;
  const float warp[3] = {0.80f, 0.66f, 0.44f}, weft[3] = {0.55f, 0.38f, 0.24f}, gap[3] = {0.18f, 0.12f, 0.08f};
  const bool horizontal = (static_cast<int>(std::floor(x / block)) + static_cast<int>(std::floor(y / block))) % 2 == 0;
  // Across a thread: a rounded profile; along it: slubs (noise) and a darker dip where it dives under.
  const float across = horizontal ? y : x, along = horizontal ? x : y;
  const float profile = std::sin(kPi * fract(across / thread));
  const float dive = 0.75f + 0.25f * std::sin(kPi * fract(along / block));
  const float slub = fbm(x, y, m, std::max(2, horizontal ? m / 16 : m / 8), std::max(2, horizontal ? m / 8 : m / 16),
                         seed, 2);
  mix(p, gap, horizontal ? warp : weft, std::clamp(profile * dive * (0.85f + 0.3f * slub), 0.0f, 1.0f));
}

}  // namespace

float tileableNoise(float x, float y, int size, int cellsX, int cellsY, unsigned seed) {
  const float fx = x * cellsX / size, fy = y * cellsY / size;
  const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
  const float tx = smooth(fx - ix), ty = smooth(fy - iy);
  const auto value = [&](int i, int j) {
    const uint32_t wi = static_cast<uint32_t>(((i % cellsX) + cellsX) % cellsX);
    const uint32_t wj = static_cast<uint32_t>(((j % cellsY) + cellsY) % cellsY);
    return (hash3(wi, wj, seed) & 0xffffff) / float(0xffffff);
  };
  const float a = value(ix, iy), b = value(ix + 1, iy), c = value(ix, iy + 1), d = value(ix + 1, iy + 1);
  return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

std::vector<std::string> proceduralExemplarNames() { return {"stripes", "scales", "weave"}; }

ExemplarImage makeProceduralExemplar(const std::string& name, int size, unsigned seed) {
  if (!isPowerOfTwo(size) || size < 16 || size > 1024)
    throw InputError("procedural exemplar size must be a power of two in [16, 1024] (got " + std::to_string(size) +
                     ")");
  void (*shade)(float, float, int, unsigned, float*) = nullptr;
  if (name == "stripes")
    shade = stripes;
  else if (name == "scales")
    shade = scales;
  else if (name == "weave")
    shade = weave;
  else
    throw InputError("unknown procedural exemplar '" + name + "' (expected stripes, scales or weave)");
  ExemplarImage img;
  img.size = size;
  img.rgb.assign(3 * static_cast<size_t>(size) * size, 0.0f);
  constexpr int kSub = 4;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      float acc[3] = {0, 0, 0}, c[3];
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx) {
          shade(x + (sx + 0.5f) / kSub, y + (sy + 0.5f) / kSub, size, seed, c);
          for (int k = 0; k < 3; ++k) acc[k] += c[k];
        }
      for (int k = 0; k < 3; ++k) img.at(x, y)[k] = acc[k] / (kSub * kSub);
    }
  return img;
}

}  // namespace tvf
