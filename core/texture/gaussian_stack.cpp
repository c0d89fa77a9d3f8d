#include "texture/gaussian_stack.h"

#include "mesh/surface_mesh.h"

namespace tvf {
namespace {

// One separable pass of [1 4 6 4 1]/16 with taps `step` pixels apart, along x (dx = 1) or y (dx = 0).
void binomialPass(const ExemplarImage& in, ExemplarImage& out, int step, bool alongX) {
  static const float w[5] = {1 / 16.f, 4 / 16.f, 6 / 16.f, 4 / 16.f, 1 / 16.f};
  const int m = in.size;
  for (int y = 0; y < m; ++y)
    for (int x = 0; x < m; ++x) {
      float acc[3] = {0, 0, 0};
      for (int t = -2; t <= 2; ++t) {
        const float* p = alongX ? in.at(x + t * step, y) : in.at(x, y + t * step);
        for (int c = 0; c < 3; ++c) acc[c] += w[t + 2] * p[c];
      }
      float* o = out.at(x, y);
      for (int c = 0; c < 3; ++c) o[c] = acc[c];
    }
}

}  // namespace

GaussianStack buildGaussianStack(const ExemplarImage& exemplar) {
  if (!isPowerOfTwo(exemplar.size) || exemplar.rgb.size() != 3 * static_cast<size_t>(exemplar.pixels()))
    throw InputError("Gaussian stack: the exemplar must be square with a power-of-two side");
  GaussianStack stack;
  stack.levels.push_back(exemplar);
  int levels = 0;
  while ((1 << levels) < exemplar.size) ++levels;
  ExemplarImage tmp = exemplar;
  for (int s = 0; s < levels; ++s) {
    const ExemplarImage& prev = stack.levels.back();
    ExemplarImage next = prev;
    binomialPass(prev, tmp, 1 << s, true);
    binomialPass(tmp, next, 1 << s, false);
    stack.levels.push_back(std::move(next));
  }
  return stack;
}

}  // namespace tvf
