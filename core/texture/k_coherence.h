#pragma once
// k-coherence candidate sets (Tong et al. 2002; Lefebvre & Hoppe 2005 Sec. 4.2): for every exemplar pixel u, the k
// exemplar pixels whose feature vectors (here: the reduced synthesis neighbourhoods) are nearest to u's,
// excluding u's own surroundings (toroidal Chebyshev distance <= radius) and keeping the k picks themselves more
// than `radius` apart, so that each candidate is a genuinely different place in the exemplar. During synthesis the
// coherent candidate (continuing a neighbour's patch) is always tried as well; these are the alternatives.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace tvf {

struct KCoherenceOptions {
  int k = 2;
  int radius = 2;      // near-self exclusion (pixels, toroidal Chebyshev)
  int pool = 8;        // nearest neighbours fetched per pixel before the separation rule picks k
  int maxChecks = 192; // points examined per query before the k-d tree search stops (0 = exact)
  // Search only on the sub-lattice of pixels whose x and y are multiples of `step` (a power of two), both as
  // queries and as answers; pixel u0 + d (0 <= d < step) then gets u0's candidates moved by d. Meant for blurred
  // stack levels (step ~ h_s / 2), where a shift by less than the blur changes a neighbourhood little.
  int step = 1;
};

struct KCoherenceLevel {
  int k = 0, radius = 0, step = 1;
  std::vector<int32_t> candidates;  // pixels x k exemplar pixel indices (y * size + x), best first
};

// Toroidal Chebyshev distance between pixel indices a and b of a size x size torus (size a power of two).
inline int toroidalChebyshev(int32_t a, int32_t b, int size) {
  const int mask = size - 1;
  int shift = 0;
  while ((1 << shift) < size) ++shift;
  const int dx = ((a & mask) - (b & mask)) & mask, dy = ((a >> shift) - (b >> shift)) & mask;
  const int ax = dx < size - dx ? dx : size - dx, ay = dy < size - dy ? dy : size - dy;
  return ax > ay ? ax : ay;
}

// `features`: pixels x D (row = y * size + x).
KCoherenceLevel kCoherence(
    const Eigen::Ref<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>& features,
    int size, const KCoherenceOptions& options = {});

}  // namespace tvf
