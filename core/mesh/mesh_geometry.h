#pragma once
// Small geometric helpers over the flat position array.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mesh/surface_mesh.h"

namespace tvf {

inline Eigen::Vector3d vertexPosition(const SurfaceMesh& mesh, int32_t v) {
  return {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
}

inline void facePositions(const SurfaceMesh& mesh, int32_t f, Eigen::Vector3d p[3]) {
  for (int c = 0; c < 3; ++c) p[c] = vertexPosition(mesh, mesh.triangles[3 * f + c]);
}

inline Eigen::Vector3d faceNormal(const SurfaceMesh& mesh, int32_t f) {
  Eigen::Vector3d p[3];
  facePositions(mesh, f, p);
  return (p[1] - p[0]).cross(p[2] - p[0]).normalized();
}

// cot of the angle between u and v.
inline double cotan(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return u.dot(v) / u.cross(v).norm();
}

}  // namespace tvf
