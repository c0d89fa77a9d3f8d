#include "constraints/surface_walk.h"

#include <cmath>
#include <string>

#include "common/input_error.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

// Walks from a to b across faces along the direction to b re-projected in each face (a discrete straight
// line on the surface). Appends crossings; returns false if it hit a boundary or gave up.
bool walkSegment(const SurfaceMesh& mesh, const MeshTopology& t, const SurfacePoint& a, const SurfacePoint& b,
                 std::vector<StrokeCrossing>& crossings) {
  const Eigen::Vector3d target = surfacePointPosition(mesh, b);
  int32_t face = a.face;
  double bary[3] = {a.bary[0], a.bary[1], a.bary[2]};
  const int maxSteps = 64 + 4 * static_cast<int>(std::sqrt(static_cast<double>(t.numFaces))) * 8;
  for (int step = 0; step < maxSteps; ++step) {
    if (face == b.face) return true;
    Eigen::Vector3d p[3];
    facePositions(mesh, face, p);
    const Eigen::Vector3d x = bary[0] * p[0] + bary[1] * p[1] + bary[2] * p[2];
    const Eigen::Vector3d d = projectToFace(mesh, face, target - x);
    if (!(d.norm() > 1e-14 * (p[1] - p[0]).norm())) return false;
    Eigen::Vector3d grad[3];
    barycentricGradients(p, grad);
    // Leave through the edge opposite the corner whose coordinate reaches zero first.
    int exitCorner = -1;
    double sMin = INFINITY;
    for (int k = 0; k < 3; ++k) {
      const double rate = grad[k].dot(d);
      if (rate < 0) {
        const double s = -bary[k] / rate;
        if (s < sMin) {
          sMin = s;
          exitCorner = k;
        }
      }
    }
    if (exitCorner < 0) return false;
    const int ci = (exitCorner + 1) % 3, cj = (exitCorner + 2) % 3;
    const int32_t e = t.edgeOf(face, ci);  // edge from corner ci to cj, opposite exitCorner
    crossings.push_back({face, e, d.normalized()});
    const int32_t next = t.otherFace(e, face);
    if (next < 0) return false;
    // Where the walk crosses, as a parameter along the edge from corner ci to cj.
    const double bi = std::max(0.0, bary[ci] + sMin * grad[ci].dot(d));
    const double bj = std::max(0.0, bary[cj] + sMin * grad[cj].dot(d));
    const double tau = bj / std::max(bi + bj, 1e-300);
    const int32_t vi = mesh.triangles[3 * face + ci], vj = mesh.triangles[3 * face + cj];
    for (int k = 0; k < 3; ++k) {
      const int32_t v = mesh.triangles[3 * next + k];
      bary[k] = v == vi ? 1 - tau : v == vj ? tau : 0.0;
    }
    face = next;
  }
  return false;
}

void validatePoint(const MeshTopology& t, const SurfacePoint& p, size_t index) {
  if (p.face < 0 || p.face >= t.numFaces)
    throw InputError("stroke point " + std::to_string(index) + " refers to face " + std::to_string(p.face) +
                     ", which does not exist");
  for (const double b : p.bary)
    if (!std::isfinite(b) || b < -1e-6 || b > 1 + 1e-6)
      throw InputError("stroke point " + std::to_string(index) +
                       " has barycentric coordinates outside [0, 1]");
  // Barycentric coordinates sum to one; [0, 0, 0] or a badly scaled triple names no point at all.
  const double sum = p.bary[0] + p.bary[1] + p.bary[2];
  if (std::abs(sum - 1) > 1e-2)
    throw InputError("stroke point " + std::to_string(index) + " has barycentric coordinates that sum to " +
                     std::to_string(sum) + " instead of 1");
}

SurfacePoint normalized(const SurfacePoint& p) {
  SurfacePoint q = p;
  double sum = 0;
  for (double& b : q.bary) sum += (b = std::max(0.0, b));
  for (double& b : q.bary) b /= sum > 0 ? sum : 1;
  if (!(sum > 0)) q.bary[0] = q.bary[1] = q.bary[2] = 1.0 / 3;
  return q;
}

}  // namespace

Eigen::Vector3d surfacePointPosition(const SurfaceMesh& mesh, const SurfacePoint& point) {
  Eigen::Vector3d p[3];
  facePositions(mesh, point.face, p);
  return point.bary[0] * p[0] + point.bary[1] * p[1] + point.bary[2] * p[2];
}

Eigen::Vector3d projectToFace(const SurfaceMesh& mesh, int32_t face, const Eigen::Vector3d& u) {
  const Eigen::Vector3d n = faceNormal(mesh, face);
  return u - n * n.dot(u);
}

StrokeWalk walkStroke(const SurfaceMesh& mesh, const MeshTopology& t,
                      const std::vector<SurfacePoint>& input) {
  if (input.size() < 2) throw InputError("a stroke needs at least two points");
  StrokeWalk walk;
  for (size_t k = 0; k < input.size(); ++k) {
    validatePoint(t, input[k], k);
    walk.points.push_back(normalized(input[k]));
  }
  for (size_t k = 0; k + 1 < walk.points.size(); ++k)
    walkSegment(mesh, t, walk.points[k], walk.points[k + 1], walk.crossings);
  return walk;
}

}  // namespace tvf
