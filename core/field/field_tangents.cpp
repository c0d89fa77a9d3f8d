#include "field/field_tangents.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>

#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

Eigen::Vector3d at(const std::vector<double>& values, int32_t v) {
  return {values[3 * v], values[3 * v + 1], values[3 * v + 2]};
}

// Any unit vector orthogonal to n.
Eigen::Vector3d anyOrthogonal(const Eigen::Vector3d& n) {
  const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(axis).normalized();
}

}  // namespace

std::vector<double> fieldTangents(const SurfaceMesh& mesh, const std::vector<double>& normals,
                                  const std::vector<double>& vertexField) {
  const int32_t n = mesh.numVertices();
  std::vector<Eigen::Vector3d> projected(n);
  double largest = 0;
  for (int32_t v = 0; v < n; ++v) {
    const Eigen::Vector3d normal = at(normals, v), u = at(vertexField, v);
    projected[v] = u - normal.dot(u) * normal;
    largest = std::max(largest, projected[v].norm());
  }
  // A fallback direction per vertex: its first edge, projected.
  std::vector<Eigen::Vector3d> fallback(n, Eigen::Vector3d::Zero());
  for (int32_t f = mesh.numFaces() - 1; f >= 0; --f) {
    for (int c = 0; c < 3; ++c) {
      const int32_t a = mesh.triangles[3 * f + c], b = mesh.triangles[3 * f + (c + 1) % 3];
      fallback[a] = vertexPosition(mesh, b) - vertexPosition(mesh, a);
    }
  }
  std::vector<double> tangents(3 * static_cast<size_t>(n));
  for (int32_t v = 0; v < n; ++v) {
    const Eigen::Vector3d normal = at(normals, v);
    Eigen::Vector3d t = projected[v];
    if (!(t.norm() > 1e-9 * largest) || largest == 0) t = fallback[v] - normal.dot(fallback[v]) * normal;
    t = t.norm() > 0 ? t.normalized() : anyOrthogonal(normal.norm() > 0 ? normal : Eigen::Vector3d::UnitZ());
    for (int d = 0; d < 3; ++d) tangents[3 * v + d] = t[d];
  }
  return tangents;
}

}  // namespace tvf
