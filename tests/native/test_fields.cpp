#include "test_fields.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "mesh/mesh_geometry.h"

namespace tvf::testing {

Eigen::VectorXd asVector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), v.size());
}

void designEveryKind(Designer& d) {
  const int32_t nF = d.mesh().numFaces();
  std::vector<SurfacePoint> points;
  for (int32_t f : {nF / 7, nF / 7 + 1, nF / 7 + 2}) points.push_back({f, {0.2, 0.3, 0.5}});
  d.addStroke(points, 1.0, 1.0);
  d.addSource(d.mesh().triangles[0], 1.0);
  d.addVortex(nF / 2, -0.5);
  d.solve();
}

SparseMatrix definiteBaseMatrix(Designer& d) {
  SparseMatrix A = d.baseMatrix();
  SparseMatrix shift(A.rows(), A.cols());
  shift.setIdentity();
  A += (1e-4 * A.diagonal().mean()) * shift;
  return A;
}

double relativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  return (asVector(a) - asVector(b)).norm() / std::max(1e-300, asVector(b).norm());
}

Eigen::Vector3d faceVector(const Designer& d, int f) {
  return Eigen::Map<const Eigen::Vector3d>(&d.faceVectors()[3 * f]);
}

Eigen::Vector3d centroid(const SurfaceMesh& m, int f) {
  Eigen::Vector3d p[3];
  facePositions(m, f, p);
  return (p[0] + p[1] + p[2]) / 3;
}

double maxRelativeError(const Designer& d, const Eigen::Vector3d& u) {
  double worst = 0;
  for (int f = 0; f < d.mesh().numFaces(); ++f)
    worst = std::max(worst, (faceVector(d, f) - u).norm() / u.norm());
  return worst;
}

std::vector<SurfacePoint> straightStroke(const SurfaceMesh& m, const Eigen::Vector3d& from,
                                         const Eigen::Vector3d& to, int samples) {
  std::vector<SurfacePoint> points;
  for (int s = 0; s <= samples; ++s) {
    const Eigen::Vector3d x = from + (to - from) * double(s) / samples;
    for (int f = 0; f < m.numFaces(); ++f) {
      Eigen::Vector3d p[3];
      facePositions(m, f, p);
      const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
      double b[3];
      for (int k = 0; k < 3; ++k)
        b[k] = (p[(k + 2) % 3] - p[(k + 1) % 3]).cross(x - p[(k + 1) % 3]).dot(n) / n.squaredNorm();
      if (b[0] >= -1e-12 && b[1] >= -1e-12 && b[2] >= -1e-12) {
        points.push_back({f, {b[0], b[1], b[2]}});
        break;
      }
    }
  }
  return points;
}

SurfacePoint surfacePointNear(const SurfaceMesh& m, const Eigen::Vector3d& x) {
  for (int f = 0; f < m.numFaces(); ++f) {
    Eigen::Vector3d p[3];
    facePositions(m, f, p);
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    const double s = n.dot(p[0]) / n.dot(x);
    if (s <= 0) continue;
    const Eigen::Vector3d y = s * x;
    double b[3];
    for (int k = 0; k < 3; ++k)
      b[k] = (p[(k + 2) % 3] - p[(k + 1) % 3]).cross(y - p[(k + 1) % 3]).dot(n) / n.squaredNorm();
    if (b[0] >= -1e-12 && b[1] >= -1e-12 && b[2] >= -1e-12) return {f, {b[0], b[1], b[2]}};
  }
  return {0, {1.0 / 3, 1.0 / 3, 1.0 / 3}};
}

}  // namespace tvf::testing
