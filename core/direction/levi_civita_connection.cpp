#include "direction/levi_civita_connection.h"

#include <cmath>

#include "mesh/mesh_geometry.h"

namespace tvf {

FaceFrames faceFrames(const SurfaceMesh& mesh, const MeshGeometry& geometry) {
  const int32_t numFaces = static_cast<int32_t>(mesh.triangles.size() / 3);
  FaceFrames frames;
  frames.e1.resize(3 * numFaces);
  frames.e2.resize(3 * numFaces);
  for (int32_t f = 0; f < numFaces; ++f) {
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    const Eigen::Vector3d n(&geometry.faceNormal[3 * f]);
    Eigen::Vector3d e1 = p[1] - p[0];
    e1 = (e1 - n * n.dot(e1)).normalized();
    if (!e1.allFinite()) e1 = Eigen::Vector3d::UnitX();  // a zero-area face: the mesh checks refuse these
    const Eigen::Vector3d e2 = n.cross(e1);
    for (int k = 0; k < 3; ++k) {
      frames.e1[3 * f + k] = e1[k];
      frames.e2[3 * f + k] = e2[k];
    }
  }
  return frames;
}

std::complex<double> inFaceFrame(const FaceFrames& frames, int32_t f, const double vector[3]) {
  const Eigen::Map<const Eigen::Vector3d> v(vector), e1(&frames.e1[3 * f]), e2(&frames.e2[3 * f]);
  return {v.dot(e1), v.dot(e2)};
}

void fromFaceFrame(const FaceFrames& frames, int32_t f, std::complex<double> z, double out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = z.real() * frames.e1[3 * f + k] + z.imag() * frames.e2[3 * f + k];
}

FaceConnection leviCivitaConnection(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                                    const FaceFrames& frames) {
  FaceConnection c;
  for (int32_t e = 0; e < t.numEdges; ++e) {
    const int32_t f = t.edgeFaces[2 * e], h = t.edgeFaces[2 * e + 1];
    if (f < 0 || h < 0) continue;
    const Eigen::Vector3d edge = edgeVector(mesh, t, e);
    const double angleF = std::arg(inFaceFrame(frames, f, edge.data()));
    const double angleG = std::arg(inFaceFrame(frames, h, edge.data()));
    const double areas = g.faceArea[f] + g.faceArea[h];
    c.faceF.push_back(f);
    c.faceG.push_back(h);
    c.angle.push_back(angleF - angleG);
    c.weight.push_back(areas > 0 ? 1.5 * edge.squaredNorm() / areas : 0.0);
  }
  return c;
}

}  // namespace tvf
