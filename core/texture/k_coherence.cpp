#include "texture/k_coherence.h"

#include <algorithm>
#include <cstdlib>

#include "mesh/surface_mesh.h"
#include "texture/kd_tree.h"

namespace tvf {

KCoherenceLevel kCoherence(
    const Eigen::Ref<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>& features,
    int size, const KCoherenceOptions& options) {
  const int n = size * size;
  if (features.rows() != n) throw InputError("k-coherence: feature rows must equal size * size");
  if (options.k < 1) throw InputError("k-coherence: k must be >= 1");
  KCoherenceLevel out;
  out.k = options.k;
  // The excluded square (2r+1)^2 must leave room for k separated picks.
  out.radius = std::clamp(options.radius, 0, std::max(0, size / 4 - 1));
  int step = 1;
  while (2 * step <= std::max(1, options.step) && 2 * step <= size / 4) step *= 2;
  out.step = step;
  const int r = out.radius, D = static_cast<int>(features.cols());
  // The lattice points, row-major, for the tree and the queries.
  const int lm = size / step, ln = lm * lm;
  std::vector<float> points(static_cast<size_t>(ln) * D);
  std::vector<int32_t> pixelOf(ln);
  for (int ly = 0; ly < lm; ++ly)
    for (int lx = 0; lx < lm; ++lx) {
      const int l = ly * lm + lx, p = ly * step * size + lx * step;
      pixelOf[l] = p;
      for (int c = 0; c < D; ++c) points[static_cast<size_t>(l) * D + c] = features(p, c);
    }
  const KdTree tree(points.data(), ln, D);
  const auto far = [&](int32_t a, int32_t b) { return toroidalChebyshev(a, b, size) > r; };

  out.candidates.resize(static_cast<size_t>(n) * options.k);
  const int pool = std::max(options.pool, 2 * options.k);
  std::vector<std::pair<float, int32_t>> found;
  std::vector<int32_t> picked;
  for (int l = 0; l < ln; ++l) {
    const int32_t u = pixelOf[l];
    tree.nearest(&points[static_cast<size_t>(l) * D], pool, [&](int32_t q) { return !far(pixelOf[q], u); }, found,
                 options.maxChecks);
    picked.clear();
    for (const auto& [dist, q] : found) {
      if (static_cast<int>(picked.size()) == options.k) break;
      bool separated = true;
      for (int32_t c : picked) separated = separated && far(pixelOf[q], c);
      if (separated) picked.push_back(pixelOf[q]);
    }
    // Too few well-separated ones (tiny or flat exemplars): the best remaining, then any far lattice pixel.
    for (const auto& [dist, q] : found) {
      if (static_cast<int>(picked.size()) == options.k) break;
      if (std::find(picked.begin(), picked.end(), pixelOf[q]) == picked.end()) picked.push_back(pixelOf[q]);
    }
    for (int t = 0; t < ln && static_cast<int>(picked.size()) < options.k; ++t) {
      const int32_t p = pixelOf[(l + ln / 2 + lm / 2 + t) % ln];
      if (far(p, u) && std::find(picked.begin(), picked.end(), p) == picked.end()) picked.push_back(p);
    }
    while (static_cast<int>(picked.size()) < options.k) picked.push_back(u);
    // Every pixel of the lattice cell gets the same candidates, moved along with it.
    for (int dy = 0; dy < step; ++dy)
      for (int dx = 0; dx < step; ++dx) {
        const int px = u % size + dx, py = u / size + dy;
        int32_t* dst = &out.candidates[(static_cast<size_t>(py) * size + px) * options.k];
        for (int j = 0; j < options.k; ++j) {
          const int cx = (picked[j] % size + dx) & (size - 1), cy = (picked[j] / size + dy) & (size - 1);
          dst[j] = cy * size + cx;
        }
      }
  }
  return out;
}

}  // namespace tvf
