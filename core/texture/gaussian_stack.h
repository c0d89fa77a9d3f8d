#pragma once
// The toroidal Gaussian stack of an exemplar (Lefebvre & Hoppe 2005, Sec. 3.1): levels at full resolution, level 0
// the exemplar itself and level s+1 level s filtered with the binomial kernel [1 4 6 4 1]/16 dilated by 2^s
// ("a trous"), separably and with wrap-around. Level s therefore carries the content of level s of a Gaussian
// pyramid (blur variance (4^s - 1)/3 pixels^2, i.e. sigma ~ 0.58 * 2^s) without being subsampled, so every exemplar
// pixel is a valid synthesis coordinate at every level; the neighbourhood spacing of level s is h_s = 2^s.
// Levels: 0 .. log2(size), the last one nearly constant.
#include <vector>

#include "texture/exemplar_image.h"

namespace tvf {

struct GaussianStack {
  std::vector<ExemplarImage> levels;  // levels[0] = exemplar
  int size() const { return levels.empty() ? 0 : levels[0].size; }
  int numLevels() const { return static_cast<int>(levels.size()); }
  static int spacing(int level) { return 1 << level; }
};

// Throws InputError if the image is not square with a power-of-two side.
GaussianStack buildGaussianStack(const ExemplarImage& exemplar);

}  // namespace tvf
