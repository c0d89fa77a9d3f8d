#pragma once
// The space synthesis compares neighbourhoods in (Lefebvre & Hoppe 2005 Sec. 4.2 with appearance vectors, 2006):
// the appearance vectors of the 8 pixels around u at the level's spacing h (offsets kNeighbourOffsets * h, the
// centre excluded), concatenated (8 x 8 = 64 numbers) and reduced by PCA to a few dimensions (8 by default).
// Each exemplar pixel's reduced vector is precomputed; the synthesizer gathers the same 8 appearance vectors around
// a synthesized texel (through the Jacobian) and projects them with the same basis, so comparing one candidate
// costs two texture fetches. Projection is linear, so it splits into one (appearance dims x dims) block per offset:
// y = sum_k block_k^T a_k - axes^T mean.
#include <Eigen/Core>

#include "texture/appearance_space.h"

namespace tvf {

// Offsets of the synthesis neighbourhood, in units of the level spacing; the GPU shaders use the same order.
constexpr int kNeighbourCount = 8;
constexpr int kNeighbourOffsets[kNeighbourCount][2] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0},
                                                       {1, 0},   {-1, 1}, {0, 1},  {1, 1}};

struct NeighbourhoodLevel {
  int level = 0, spacing = 1;
  PcaBasis basis;           // (8 * appearance dims) -> dims
  RowMatrixXf vectors;  // pixels x dims
};

// pixels x (8 * appearance dims): the appearance vectors at u + h * offset_k, k-major.
RowMatrixXf gatherNeighbourhoods(const AppearanceLevel& appearance, int size);
NeighbourhoodLevel neighbourhoodLevel(const AppearanceLevel& appearance, int size, int dims = 8,
                                      int covarianceSubsample = 1);

}  // namespace tvf
