#include "texture/neighbourhood_space.h"

namespace tvf {

RowMatrixXf gatherNeighbourhoods(const AppearanceLevel& appearance, int size) {
  const int a = static_cast<int>(appearance.vectors.cols());
  const int h = appearance.spacing, mask = size - 1;
  RowMatrixXf out(static_cast<Eigen::Index>(size) * size, kNeighbourCount * a);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const Eigen::Index row = static_cast<Eigen::Index>(y) * size + x;
      for (int k = 0; k < kNeighbourCount; ++k) {
        const int nx = (x + kNeighbourOffsets[k][0] * h) & mask, ny = (y + kNeighbourOffsets[k][1] * h) & mask;
        out.block(row, k * a, 1, a) = appearance.vectors.row(static_cast<Eigen::Index>(ny) * size + nx);
      }
    }
  return out;
}

NeighbourhoodLevel neighbourhoodLevel(const AppearanceLevel& appearance, int size, int dims, int covarianceSubsample) {
  NeighbourhoodLevel out;
  out.level = appearance.level;
  out.spacing = appearance.spacing;
  const RowMatrixXf raw = gatherNeighbourhoods(appearance, size);
  out.basis = pcaOfRows(raw, dims, covarianceSubset(size, covarianceSubsample));
  out.vectors = pcaProject(out.basis, raw);
  return out;
}

}  // namespace tvf
