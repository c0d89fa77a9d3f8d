#include "mesh/closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tvf {

// Ericson, "Real-Time Collision Detection", 5.1.5: by the Voronoi regions of the vertices, edges and face.
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double sum = va + vb + vc;
  if (!(sum > 0)) return a;  // a degenerate triangle: its first corner
  return a + ab * (vb / sum) + ac * (vc / sum);
}

TriangleGrid::TriangleGrid(const std::vector<double>& positions, const std::vector<int32_t>& triangles)
    : positions_(positions), triangles_(triangles) {
  const long nt = static_cast<long>(triangles.size() / 3);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (std::size_t v = 0; v + 2 < positions.size(); v += 3) {
    const Eigen::Vector3d x(positions[v], positions[v + 1], positions[v + 2]);
    lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  }
  if (nt == 0) {
    cellStart_.assign(2, 0);
    return;
  }
  origin_ = lo;
  const Eigen::Vector3d extent = (hi - lo).cwiseMax(1e-12);
  // Cells twice the mean triangle's size, and not more than about 16M of them.
  double meanSize = 0;
  for (long t = 0; t < nt; ++t) {
    Eigen::Vector3d a = vertex(triangles_[3 * t]), b = a;
    for (int c = 1; c < 3; ++c)
      a = a.cwiseMin(vertex(triangles_[3 * t + c])), b = b.cwiseMax(vertex(triangles_[3 * t + c]));
    meanSize += (b - a).maxCoeff() / nt;
  }
  cell_ = std::max({2 * meanSize, std::cbrt(extent.prod() / 16e6), extent.maxCoeff() * 1e-6});
  for (int k = 0; k < 3; ++k)
    dims_[k] = std::max<long>(1, static_cast<long>(std::ceil(extent[k] / cell_)) + 1);
  const long cells = dims_[0] * dims_[1] * dims_[2];
  std::vector<int32_t> count(cells + 1, 0);
  auto forCells = [&](long t, auto&& visit) {
    Eigen::Vector3d a = vertex(triangles_[3 * t]), b = a;
    for (int c = 1; c < 3; ++c)
      a = a.cwiseMin(vertex(triangles_[3 * t + c])), b = b.cwiseMax(vertex(triangles_[3 * t + c]));
    long i0[3], i1[3];
    for (int k = 0; k < 3; ++k) {
      i0[k] = std::clamp<long>(static_cast<long>((a[k] - origin_[k]) / cell_), 0, dims_[k] - 1);
      i1[k] = std::clamp<long>(static_cast<long>((b[k] - origin_[k]) / cell_), 0, dims_[k] - 1);
    }
    for (long i = i0[0]; i <= i1[0]; ++i)
      for (long j = i0[1]; j <= i1[1]; ++j)
        for (long k = i0[2]; k <= i1[2]; ++k) visit(cellIndex(i, j, k));
  };
  for (long t = 0; t < nt; ++t) forCells(t, [&](long c) { ++count[c + 1]; });
  for (long c = 0; c < cells; ++c) count[c + 1] += count[c];
  cellStart_ = count;
  cellTriangles_.resize(count[cells]);
  for (long t = 0; t < nt; ++t)
    forCells(t, [&](long c) { cellTriangles_[count[c]++] = static_cast<int32_t>(t); });
}

double TriangleGrid::distance(const Eigen::Vector3d& p, double bound) const {
  if (cellTriangles_.empty()) return std::numeric_limits<double>::infinity();
  long c0[3];
  for (int k = 0; k < 3; ++k)
    c0[k] = std::clamp<long>(static_cast<long>(std::floor((p[k] - origin_[k]) / cell_)), 0, dims_[k] - 1);
  double best = std::numeric_limits<double>::infinity();
  const long maxRing = std::max({dims_[0], dims_[1], dims_[2]});
  for (long r = 0; r <= maxRing; ++r) {
    for (long i = c0[0] - r; i <= c0[0] + r; ++i)
      for (long j = c0[1] - r; j <= c0[1] + r; ++j)
        for (long k = c0[2] - r; k <= c0[2] + r; ++k) {
          if (std::max({std::abs(i - c0[0]), std::abs(j - c0[1]), std::abs(k - c0[2])}) != r) continue;
          if (i < 0 || j < 0 || k < 0 || i >= dims_[0] || j >= dims_[1] || k >= dims_[2]) continue;
          const long c = cellIndex(i, j, k);
          for (int32_t s = cellStart_[c]; s < cellStart_[c + 1]; ++s) {
            const int32_t t = cellTriangles_[s];
            const Eigen::Vector3d q = closestPointOnTriangle(
                p, vertex(triangles_[3 * t]), vertex(triangles_[3 * t + 1]), vertex(triangles_[3 * t + 2]));
            best = std::min(best, (q - p).norm());
            if (best <= bound) return best;
          }
        }
    // Every triangle not yet seen lies outside the cells within ring r, at least r cells away.
    if (best <= r * cell_) break;
  }
  return best;
}

}  // namespace tvf
