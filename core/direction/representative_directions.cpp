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

VertexTangentAxes vertexTangentAxes(const SurfaceMesh& mesh) {
  const std::vector<double> normals = vertexNormals(mesh);
  const size_t numVertices = normals.size() / 3;
  VertexTangentAxes axes;
  axes.a.resize(3 * numVertices);
  axes.b.resize(3 * numVertices);
  for (size_t v = 0; v < numVertices; ++v) {
    // Any fixed direction not along the normal.
    const Eigen::Vector3d n(&normals[3 * v]);
    Eigen::Vector3d a = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    a = (a - n * n.dot(a)).normalized();
    const Eigen::Vector3d b = n.cross(a);
    for (int k = 0; k < 3; ++k) {
      axes.a[3 * v + k] = a[k];
      axes.b[3 * v + k] = b[k];
    }
  }
  return axes;
}

std::vector<double> vertexRepresentatives(const SurfaceMesh& mesh, const MeshTopology& t,
                                          const MeshGeometry& g, const std::vector<double>& faceDirections,
                                          int symmetry) {
  std::vector<double> out;
  vertexRepresentatives(vertexTangentAxes(mesh), mesh, t, g, faceDirections, symmetry, out);
  return out;
}

// A unit complex number raised to the N-th power by multiplication: the N-th power of a direction without an
// angle (atan2 and a sine and cosine per corner took most of a stroke's read-out at 1.25M edges), written out
// in reals (a complex product checks for infinities and NaN through a library call).
static std::complex<double> unitPower(double re, double im, int symmetry) {
  double pr = re, pi = im;
  for (int k = 1; k < symmetry; ++k) {
    const double r = pr * re - pi * im;
    pi = pr * im + pi * re;
    pr = r;
  }
  return {pr, pi};
}

void vertexRepresentatives(const VertexTangentAxes& axes, const SurfaceMesh& mesh, const MeshTopology& t,
                           const MeshGeometry& g, const std::vector<double>& faceDirections, int symmetry,
                           std::vector<double>& out) {
  std::vector<std::complex<double>> sum(t.numVertices, 0.0);
  for (int32_t f = 0; f < t.numFaces; ++f) {
    const double* d = &faceDirections[3 * f];
    for (int c = 0; c < 3; ++c) {
      const int32_t v = mesh.triangles[3 * f + c];
      const double* a = &axes.a[3 * v];
      const double* b = &axes.b[3 * v];
      const double x = d[0] * a[0] + d[1] * a[1] + d[2] * a[2];
      const double y = d[0] * b[0] + d[1] * b[1] + d[2] * b[2];
      // Face directions are unit: the projection's length needs no guard against overflow (hypot's).
      const double length = std::sqrt(x * x + y * y);
      if (length > 0) sum[v] += g.faceArea[f] * unitPower(x / length, y / length, symmetry);
    }
  }
  out.assign(3 * t.numVertices, 0.0);
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (sum[v] == 0.0) continue;
    const double theta = std::arg(sum[v]) / symmetry;
    const double c = std::cos(theta), s = std::sin(theta);
    for (int k = 0; k < 3; ++k) out[3 * v + k] = c * axes.a[3 * v + k] + s * axes.b[3 * v + k];
  }
}

double symmetricAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& normal,
                      int symmetry) {
  const double angle = std::atan2(a.cross(b).dot(normal), a.dot(b));
  return std::arg(std::polar(1.0, symmetry * angle)) / symmetry;
}

}  // namespace tvf
