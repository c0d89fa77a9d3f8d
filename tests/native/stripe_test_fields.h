#pragma once
// Fields and read-outs the stripe tests share (stripe_pattern_test.cpp, design_stripes_test.cpp).
#include <Eigen/Core>
#include <vector>

#include "direction/stripe_pattern.h"
#include "mesh/mesh_geometry.h"
#include "mesh/surface_mesh.h"

namespace tvf::testing {

// The gradient of sum_k b_k g_k on a face (the regular part of a family's phase).
inline Eigen::Vector3d phaseGradient(const SurfaceMesh& mesh, const StripePattern& p, int family, int32_t f) {
  Eigen::Vector3d pos[3], grad[3];
  facePositions(mesh, f, pos);
  barycentricGradients(pos, grad);
  const size_t slot = static_cast<size_t>(family) * mesh.numFaces() + f;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) g += p.cornerPhase[3 * slot + k] * grad[k];
  return g;
}

inline std::vector<double> constantField(const SurfaceMesh& m, const Eigen::Vector3d& d) {
  std::vector<double> out;
  for (int32_t v = 0; v < m.numVertices(); ++v) out.insert(out.end(), {d.x(), d.y(), d.z()});
  return out;
}

// Around the tube of torus(n, m, 2, r) (the direction of increasing minor angle), unit.
inline std::vector<double> aroundTheTube(const SurfaceMesh& m) {
  std::vector<double> out;
  for (int32_t v = 0; v < m.numVertices(); ++v) {
    const Eigen::Vector3d p = vertexPosition(m, v);
    const Eigen::Vector3d centre = 2.0 * Eigen::Vector3d(p.x(), p.y(), 0).normalized();
    const Eigen::Vector3d t = Eigen::Vector3d(-p.y(), p.x(), 0).normalized().cross((p - centre).normalized());
    out.insert(out.end(), {t.x(), t.y(), t.z()});
  }
  return out;
}

}  // namespace tvf::testing
