#pragma once
// Distances from points to a triangle soup, through a uniform grid of the triangles' bounding boxes: for
// measuring one surface against another (a remeshed surface's Hausdorff distance to its input).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace tvf {

// The point of triangle (a, b, c) closest to p.
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c);

class TriangleGrid {
 public:
  // positions: 3 per vertex; triangles: 3 per triangle. Both must outlive the grid.
  TriangleGrid(const std::vector<double>& positions, const std::vector<int32_t>& triangles);
  // The distance from p to the nearest triangle (infinity when there are none). With a bound, the search
  // stops at the first triangle within it and returns that triangle's distance (at most the bound): a
  // Hausdorff distance needs a point's own distance only where it is beyond the largest one so far.
  double distance(const Eigen::Vector3d& p, double bound = -1) const;

 private:
  Eigen::Vector3d vertex(int32_t v) const {
    return {positions_[3 * v], positions_[3 * v + 1], positions_[3 * v + 2]};
  }
  long cellIndex(long i, long j, long k) const { return (i * dims_[1] + j) * dims_[2] + k; }

  const std::vector<double>& positions_;
  const std::vector<int32_t>& triangles_;
  Eigen::Vector3d origin_;
  double cell_ = 1;
  long dims_[3] = {1, 1, 1};
  std::vector<int32_t> cellStart_, cellTriangles_;  // CSR
};

}  // namespace tvf
