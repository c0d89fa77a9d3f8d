#include "field/singularities.h"

#include <cmath>

#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

constexpr double kTwoPi = 6.283185307179586;

double wrapAngle(double a) {
  return a - kTwoPi * std::floor((a + M_PI) / kTwoPi);
}

// Angle from direction `edge` to `u`, measured counter-clockwise about the face normal n.
double angleFromEdge(const Eigen::Vector3d& edge, const Eigen::Vector3d& u, const Eigen::Vector3d& n) {
  return std::atan2(edge.cross(u).dot(n), edge.dot(u));
}

int cornerOf(const SurfaceMesh& mesh, int32_t f, int32_t v) {
  for (int c = 0; c < 3; ++c)
    if (mesh.triangles[3 * f + c] == v) return c;
  return -1;
}

}  // namespace

std::vector<Singularity> findSingularities(const SurfaceMesh& mesh, const MeshTopology& t,
                                           const std::vector<double>& faceVectors) {
  double maxNorm = 0;
  for (int32_t f = 0; f < t.numFaces; ++f)
    maxNorm = std::max(maxNorm, Eigen::Map<const Eigen::Vector3d>(&faceVectors[3 * f]).norm());
  const double tiny = 1e-10 * maxNorm;
  std::vector<int32_t> startFace(t.numVertices, -1);
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int c = 0; c < 3; ++c) startFace[mesh.triangles[3 * f + c]] = f;
  std::vector<Singularity> result;
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (t.isBoundaryVertex[v] || startFace[v] < 0 || maxNorm == 0) continue;
    double turning = 0, angleSum = 0;
    bool defined = true;
    int32_t f = startFace[v];
    const int32_t valence = t.vertexFaceCount[v];
    for (int32_t step = 0; step < valence && defined; ++step) {
      const int c = cornerOf(mesh, f, v);
      const int32_t b = mesh.triangles[3 * f + (c + 2) % 3];
      const int32_t shared =
          t.edgeOf(f, (c + 2) % 3);  // edge (b -> v): leads to the next face counter-clockwise
      const int32_t g = t.edgeFaces[2 * shared] == f ? t.edgeFaces[2 * shared + 1] : t.edgeFaces[2 * shared];
      const Eigen::Vector3d uf = Eigen::Map<const Eigen::Vector3d>(&faceVectors[3 * f]);
      const Eigen::Vector3d ug = Eigen::Map<const Eigen::Vector3d>(&faceVectors[3 * g]);
      if (uf.norm() <= tiny || ug.norm() <= tiny) defined = false;
      const Eigen::Vector3d edge = vertexPosition(mesh, b) - vertexPosition(mesh, v);
      turning += wrapAngle(angleFromEdge(edge, ug, faceNormal(mesh, g)) -
                           angleFromEdge(edge, uf, faceNormal(mesh, f)));
      Eigen::Vector3d p[3];
      facePositions(mesh, f, p);
      angleSum += std::acos(std::clamp(
          (p[(c + 1) % 3] - p[c]).normalized().dot((p[(c + 2) % 3] - p[c]).normalized()), -1.0, 1.0));
      f = g;
    }
    if (!defined) continue;
    const double index = std::round((turning + kTwoPi - angleSum) / kTwoPi);
    if (index != 0) result.push_back({v, index});
  }
  return result;
}

}  // namespace tvf
