#include "mesh/icosphere.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace tvf {

SurfaceMesh icosphere(int subdivisions) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  SurfaceMesh m;
  m.positions = {-1, g,  0,  1, g, 0,  -1, -g, 0,  1, -g, 0, 0,  -1, g,  0,  1, g,
                 0,  -1, -g, 0, 1, -g, g,  0,  -1, g, 0,  1, -g, 0,  -1, -g, 0, 1};
  m.triangles = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                 6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int32_t, int32_t>, int32_t> midpoint;
    const auto mid = [&](int32_t a, int32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      for (int d = 0; d < 3; ++d)
        m.positions.push_back(0.5 * (m.positions[3 * a + d] + m.positions[3 * b + d]));
      return midpoint[key] = m.numVertices() - 1;
    };
    std::vector<int32_t> next;
    next.reserve(4 * m.triangles.size());
    for (int32_t f = 0; f < m.numFaces(); ++f) {
      const int32_t a = m.triangles[3 * f], b = m.triangles[3 * f + 1], c = m.triangles[3 * f + 2];
      const int32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    m.triangles = std::move(next);
  }
  for (int32_t v = 0; v < m.numVertices(); ++v) {
    double* p = &m.positions[3 * v];
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int d = 0; d < 3; ++d) p[d] /= r;
  }
  return m;
}

}  // namespace tvf
