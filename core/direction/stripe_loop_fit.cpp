// SPDX-License-Identifier: GPL-2.0-or-later
#include "direction/stripe_loop_fit.h"

#include <algorithm>
#include <cmath>

#include "common/angles.h"
#include "mesh/mesh_geometry.h"

namespace tvf::stripe {

bool hasLoops(const MeshTopology& t) {
  for (const ComponentInfo& c : t.components)
    if (c.genus > 0 || c.boundaryLoops > 1) return true;
  return false;
}

FitScore fitScore(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g, const Families& fam,
                  const EdgeTurns& turns, const StripeOptions& o, const std::vector<double>& psi,
                  const std::vector<double>& turn, const std::vector<uint8_t>& near) {
  const bool turned = turn.size() == static_cast<size_t>(t.numVertices) * fam.count;
  FitScore score;
  double area = 0, sum = 0;
  for (int32_t f = 0; f < t.numFaces; ++f) {
    if (near[f] || g.faceArea[f] <= 0) continue;
    Eigen::Vector3d p[3], grad[3];
    facePositions(mesh, f, p);
    barycentricGradients(p, grad);
    const Eigen::Vector3d normal(&g.faceNormal[3 * static_cast<size_t>(f)]);
    for (int s = 0; s < fam.count; ++s) {
      const FaceLift l = liftFace(mesh, t, fam, turns, o, psi, f, s);
      if (l.fieldSingular) continue;
      if (l.n != 0) {
        ++score.breaks;
        continue;
      }
      Eigen::Vector3d gradient = Eigen::Vector3d::Zero(), growth = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        const size_t at = static_cast<size_t>(l.v[k]) * fam.count + l.family[k];
        gradient += (l.alpha[k] + (turned ? l.sign[k] * turn[at] : 0)) * grad[k];
        growth += l.sign[k] * fam.growth[at];
      }
      growth -= growth.dot(normal) * normal;
      const double norms = gradient.norm() * growth.norm();
      if (norms <= 0) continue;
      sum += g.faceArea[f] * std::acos(std::min(1.0, std::abs(gradient.dot(growth)) / norms));
      area += g.faceArea[f];
    }
  }
  score.degrees = area > 0 ? sum / area * 180 / kPi : 0;
  return score;
}

}  // namespace tvf::stripe
