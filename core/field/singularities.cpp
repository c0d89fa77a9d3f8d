#include "field/singularities.h"

#include <cmath>
#include <complex>

#include "common/angles.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

// u as a complex number in the frame of `edge` (real axis) in the face with normal n: transport across the
// edge by unfolding keeps this number, so the jump between two faces is the argument of their ratio.
std::complex<double> inEdgeFrame(const Eigen::Vector3d& edge, const Eigen::Vector3d& u, const double* n) {
  const Eigen::Vector3d normal(n[0], n[1], n[2]);
  return {edge.dot(u), edge.cross(u).dot(normal)};
}

}  // namespace

std::vector<Singularity> findSingularities(const SurfaceMesh& mesh, const MeshTopology& t,
                                           const MeshGeometry& g, const std::vector<double>& faceVectors,
                                           int symmetry) {
  double maxNorm = 0;
  for (int32_t f = 0; f < t.numFaces; ++f)
    maxNorm = std::max(maxNorm, Eigen::Map<const Eigen::Vector3d>(&faceVectors[3 * f]).norm());
  const double tiny = 1e-10 * maxNorm;
  std::vector<int32_t> startFace(t.numVertices, -1);
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int c = 0; c < 3; ++c) startFace[mesh.triangles[3 * f + c]] = f;
  std::vector<Singularity> result;
  if (maxNorm == 0) return result;
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (t.isBoundaryVertex[v] || startFace[v] < 0) continue;
    double turning = 0;
    bool defined = true;
    int32_t f = startFace[v];
    const Eigen::Vector3d pv = vertexPosition(mesh, v);
    for (int32_t step = 0; step < t.vertexFaceCount[v] && defined; ++step) {
      const int c = mesh.cornerOf(f, v);
      // Edge (b -> v) of f leads to the next face counter-clockwise around v.
      const int32_t shared = t.edgeOf(f, (c + 2) % 3);
      const int32_t next = t.otherFace(shared, f);
      const Eigen::Map<const Eigen::Vector3d> uf(&faceVectors[3 * f]), ug(&faceVectors[3 * next]);
      if (uf.norm() <= tiny || ug.norm() <= tiny) defined = false;
      const Eigen::Vector3d edge = vertexPosition(mesh, mesh.triangles[3 * f + (c + 2) % 3]) - pv;
      const std::complex<double> jump = inEdgeFrame(edge, ug, &g.faceNormal[3 * next]) *
                                        std::conj(inEdgeFrame(edge, uf, &g.faceNormal[3 * f]));
      turning += symmetry == 1 ? std::arg(jump) : std::arg(std::pow(jump, symmetry)) / symmetry;
      f = next;
    }
    if (!defined) continue;
    const double index = std::round(symmetry * (turning + g.angleDefect[v]) / kTwoPi) / symmetry;
    if (index != 0) result.push_back({v, index});
  }
  return result;
}

}  // namespace tvf
