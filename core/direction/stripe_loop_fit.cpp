// SPDX-License-Identifier: GPL-2.0-or-later
#include "direction/stripe_loop_fit.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "common/angles.h"
#include "mesh/mesh_geometry.h"

namespace tvf::stripe {

bool hasLoops(const MeshTopology& t) {
  for (const ComponentInfo& c : t.components)
    if (c.genus > 0 || c.boundaryLoops > 1) return true;
  return false;
}

FitScore fitScore(const SurfaceMesh& mesh, const MeshTopology& t, const Families& fam, const EdgeTurns& turns,
                  const StripeOptions& o, const std::vector<double>& psi, const std::vector<double>& turn,
                  const std::vector<uint8_t>& near) {
  const bool turned = turn.size() == static_cast<size_t>(t.numVertices) * fam.count;
  FitScore score;
  double area = 0, sum = 0;
  for (int32_t f = 0; f < t.numFaces; ++f) {
    if (near[f]) continue;
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    const FaceNormalArea na = faceNormalArea(p);
    if (na.area <= 0) continue;
    for (int s = 0; s < fam.count; ++s) {
      const FaceLift l = liftFace(mesh, t, fam, turns, o, psi, f, s);
      if (l.fieldSingular) continue;
      if (l.n != 0) {
        ++score.breaks;
        continue;
      }
      Eigen::Vector3d gradient = Eigen::Vector3d::Zero(), growth = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        const double phase =
            l.alpha[k] +
            (turned ? l.sign[k] * turn[static_cast<size_t>(l.v[k]) * fam.count + l.family[k]] : 0);
        gradient += phase * na.normal.cross(p[(k + 2) % 3] - p[(k + 1) % 3]);
        growth += l.sign[k] * fam.growth[static_cast<size_t>(l.v[k]) * fam.count + l.family[k]];
      }
      growth -= growth.dot(na.normal) * na.normal;
      const double norms = gradient.norm() * growth.norm();
      if (norms <= 0) continue;
      sum += na.area * std::acos(std::min(1.0, std::abs(gradient.dot(growth)) / norms));
      area += na.area;
    }
  }
  score.degrees = area > 0 ? sum / area * 180 / kPi : 0;
  return score;
}

std::vector<uint8_t> nearSingularities(const SurfaceMesh& mesh, const MeshTopology& t,
                                       const std::vector<uint8_t>& turns, double radius) {
  std::vector<Eigen::Vector3d> centroid(t.numFaces);
  std::vector<double> distance(t.numFaces, std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int32_t f = 0; f < t.numFaces; ++f) {
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    centroid[f] = (p[0] + p[1] + p[2]) / 3.0;
    if (turns[f]) distance[f] = 0, queue.push({0.0, f});
  }
  while (!queue.empty()) {
    const auto [d, f] = queue.top();
    queue.pop();
    if (d > distance[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const int32_t h = t.otherFace(t.edgeOf(f, k), f);
      if (h < 0) continue;
      const double dh = d + (centroid[h] - centroid[f]).norm();
      if (dh <= radius && dh < distance[h]) distance[h] = dh, queue.push({dh, h});
    }
  }
  std::vector<uint8_t> near(t.numFaces, 0);
  for (int32_t f = 0; f < t.numFaces; ++f) near[f] = std::isfinite(distance[f]);
  return near;
}

}  // namespace tvf::stripe
