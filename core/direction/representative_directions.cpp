#include "direction/representative_directions.h"

#include <cmath>
#include <complex>

#include "mesh/mesh_geometry.h"

namespace tvf {

std::vector<double> faceRepresentatives(const FaceFrames& frames, const Eigen::VectorXd& power,
                                        int symmetry) {
  const int32_t numFaces = static_cast<int32_t>(power.size() / 2);
  std::vector<double> out(3 * numFaces, 0.0);
  for (int32_t f = 0; f < numFaces; ++f) {
    const std::complex<double> u(power[2 * f], power[2 * f + 1]);
    if (u == 0.0) continue;
    fromFaceFrame(frames, f, std::polar(1.0, std::arg(u) / symmetry), &out[3 * f]);
  }
  return out;
}

std::vector<double> vertexRepresentatives(const SurfaceMesh& mesh, const MeshTopology& t,
                                          const MeshGeometry& g, const std::vector<double>& faceDirections,
                                          int symmetry) {
  const std::vector<double> normals = vertexNormals(mesh);
  std::vector<std::complex<double>> sum(t.numVertices, 0.0);
  std::vector<double> out(3 * t.numVertices, 0.0);
  // One tangent axis per vertex: any fixed direction not along its normal.
  auto axes = [&](int32_t v, Eigen::Vector3d& a, Eigen::Vector3d& b) {
    const Eigen::Vector3d n(&normals[3 * v]);
    a = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    a = (a - n * n.dot(a)).normalized();
    b = n.cross(a);
  };
  for (int32_t f = 0; f < t.numFaces; ++f) {
    const Eigen::Vector3d d(&faceDirections[3 * f]);
    for (int c = 0; c < 3; ++c) {
      const int32_t v = mesh.triangles[3 * f + c];
      Eigen::Vector3d a, b;
      axes(v, a, b);
      const std::complex<double> z(d.dot(a), d.dot(b));
      if (std::abs(z) > 0) sum[v] += g.faceArea[f] * std::polar(1.0, symmetry * std::arg(z));
    }
  }
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (sum[v] == 0.0) continue;
    Eigen::Vector3d a, b;
    axes(v, a, b);
    const double theta = std::arg(sum[v]) / symmetry;
    const Eigen::Vector3d r = std::cos(theta) * a + std::sin(theta) * b;
    for (int k = 0; k < 3; ++k) out[3 * v + k] = r[k];
  }
  return out;
}

double symmetricAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& normal,
                      int symmetry) {
  const double angle = std::atan2(a.cross(b).dot(normal), a.dot(b));
  return std::arg(std::polar(1.0, symmetry * angle)) / symmetry;
}

}  // namespace tvf
