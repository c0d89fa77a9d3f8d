#pragma once
// Fields and read-outs the stripe tests share (stripe_pattern_test.cpp, design_stripes_test.cpp).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "direction/stripe_pattern.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
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

// The phase at barycentric b in face f of a family.
inline double phaseAt(const StripePattern& p, int32_t nF, int family, int32_t f, const double b[3]) {
  const size_t slot = static_cast<size_t>(family) * nF + f;
  double x = 0;
  for (int k = 0; k < 3; ++k) x += b[k] * p.cornerPhase[3 * slot + k];
  return x + p.branchIndex[slot] * stripeAngle(b[0], b[1], b[2]);
}

// The largest difference (mod 2 pi) between the phases the two faces of an interior edge give its points, for
// one family of the first face. A cross field's families may swap labels across an edge and a line's phase
// run the other way (`families` > 1 or `signs`): then against the nearest of the second face's families,
// either way. Edges of faces round which the field's representatives do not match up are left out: their
// phase is unwrapped along two of their edges.
inline double worstEdgeDisagreement(const SurfaceMesh& m, const MeshTopology& t, const StripePattern& p,
                                    int family, int families = 1, bool signs = false) {
  double worst = 0;
  for (int32_t e = 0; e < t.numEdges; ++e) {
    if (t.isBoundaryEdge[e]) continue;
    const int32_t va = t.edgeVertices[2 * e], vb = t.edgeVertices[2 * e + 1];
    const int32_t f = t.edgeFaces[2 * e], g = t.edgeFaces[2 * e + 1];
    if (!p.fieldSingular.empty() && (p.fieldSingular[f] || p.fieldSingular[g])) continue;
    double b[2][3] = {{0, 0, 0}, {0, 0, 0}};
    double best = 1e300;
    for (int other = 0; other < families; ++other)
      for (double sign : {1.0, -1.0}) {
        if (sign < 0 && !signs) continue;
        double gap = 0;
        for (double s : {0.0, 0.25, 0.5, 0.8, 1.0}) {
          for (int side = 0; side < 2; ++side)
            for (int k = 0; k < 3; ++k) {
              const int32_t v = m.triangles[3 * (side ? g : f) + k];
              b[side][k] = v == va ? 1 - s : v == vb ? s : 0;
            }
          const double a = phaseAt(p, m.numFaces(), family, f, b[0]);
          const double c = phaseAt(p, m.numFaces(), families > 1 ? other : family, g, b[1]);
          gap = std::max(gap, std::abs(std::remainder(a - sign * c, 2 * M_PI)));
        }
        best = std::min(best, gap);
      }
    worst = std::max(worst, best);
  }
  return worst;
}

// Face f's stripes' angle to a vertex field (radians, as lines: the family's phase gradient against the
// corners' field summed and turned a quarter in the face), and the face's area.
struct FaceAngle {
  double angle = 0, area = 0;
};
inline FaceAngle angleOffTheField(const SurfaceMesh& m, const StripePattern& p,
                                  const std::vector<double>& field, int32_t f, int family = 0) {
  Eigen::Vector3d pos[3];
  facePositions(m, f, pos);
  const FaceNormalArea na = faceNormalArea(pos);
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) d += Eigen::Map<const Eigen::Vector3d>(&field[3 * m.triangles[3 * f + k]]);
  const Eigen::Vector3d g = phaseGradient(m, p, family, f).normalized(),
                        across = na.normal.cross(d).normalized();
  return {std::acos(std::min(1.0, std::abs(g.dot(across)))), na.area};
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
