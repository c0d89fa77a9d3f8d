#include "mesh/mesh_geometry.h"

namespace tvf {

std::vector<double> vertexNormals(const SurfaceMesh& mesh) {
  std::vector<double> normals(3 * static_cast<size_t>(mesh.numVertices()), 0.0);
  for (int32_t f = 0; f < mesh.numFaces(); ++f) {
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    // Weighted by twice the area: the normalization below takes the common factor out exactly.
    const Eigen::Vector3d weighted = twiceAreaNormal(p);
    for (int c = 0; c < 3; ++c) {
      const int32_t v = mesh.triangles[3 * f + c];
      for (int d = 0; d < 3; ++d) normals[3 * v + d] += weighted[d];
    }
  }
  for (int32_t v = 0; v < mesh.numVertices(); ++v) {
    Eigen::Map<Eigen::Vector3d> n(&normals[3 * v]);
    const double length = n.norm();
    n = length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
  }
  return normals;
}

}  // namespace tvf
