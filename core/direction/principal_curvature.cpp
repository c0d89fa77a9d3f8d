#include "direction/principal_curvature.h"

#include <cmath>
#include <string>

#include "common/input_error.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

// Signed dihedral angle at an interior edge: positive where the surface bends away from its normals (convex).
double dihedralAngle(const SurfaceMesh& mesh, const MeshGeometry& g, int32_t f, int32_t h) {
  const Eigen::Vector3d nf(&g.faceNormal[3 * f]), nh(&g.faceNormal[3 * h]);
  Eigen::Vector3d pf[3], ph[3];
  facePositions(mesh, f, pf);
  facePositions(mesh, h, ph);
  const Eigen::Vector3d towards = (ph[0] + ph[1] + ph[2] - pf[0] - pf[1] - pf[2]) / 3;
  const double angle = std::atan2(nf.cross(nh).norm(), nf.dot(nh));
  return (nh - nf).dot(towards) >= 0 ? angle : -angle;
}

}  // namespace

std::vector<std::complex<double>> principalCurvaturePower(const SurfaceMesh& mesh, const MeshTopology& t,
                                                          const MeshGeometry& g, const FaceFrames& frames,
                                                          int symmetry) {
  if (symmetry % 2 != 0)
    throw InputError(
        "curvature alignment needs an even symmetry (a line or cross field): principal "
        "directions have no sign; symmetry " +
        std::to_string(symmetry) + " was asked for");
  std::vector<std::complex<double>> z(t.numFaces, 0.0);
  for (int32_t e = 0; e < t.numEdges; ++e) {
    const int32_t f = t.edgeFaces[2 * e], h = t.edgeFaces[2 * e + 1];
    if (f < 0 || h < 0) continue;
    const double beta = dihedralAngle(mesh, g, f, h);
    const Eigen::Vector3d edge = edgeVector(mesh, t, e);
    for (const int32_t face : {f, h}) {
      if (!(g.faceArea[face] > 0)) continue;
      const Eigen::Vector3d normal(&g.faceNormal[3 * face]);
      const Eigen::Vector3d across = normal.cross(edge);  // |e| long, in the face's plane
      const std::complex<double> a = inFaceFrame(frames, face, across.data());
      // (beta |e| / 2) t t' contributes (beta |e| / 2) e^{2 i phi} to the trace-free part; a^2 / |e| is that.
      z[face] += 0.5 * beta * a * a / (edge.norm() * g.faceArea[face]);
    }
  }
  std::vector<std::complex<double>> q(t.numFaces);
  double sum = 0, area = 0;
  for (int32_t f = 0; f < t.numFaces; ++f) {
    const double r = std::abs(z[f]);
    q[f] = r > 0 ? std::polar(r, (symmetry / 2) * std::arg(z[f])) : 0.0;
    sum += g.faceArea[f] * r * r;
    area += g.faceArea[f];
  }
  const double rms = std::sqrt(sum / std::max(area, 1e-300));
  if (rms > 0)
    for (auto& value : q) value /= rms;
  return q;
}

}  // namespace tvf
