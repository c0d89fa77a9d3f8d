#include "mesh/face_adjacency.h"

#include "mesh/mesh_geometry.h"

namespace tvf {

std::vector<int32_t> halfEdgeTwins(const MeshTopology& t) {
  std::vector<int32_t> twin(t.faceEdges.size(), -1);
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int c = 0; c < 3; ++c) {
      const int32_t e = t.faceEdges[3 * f + c], g = t.otherFace(e, f);
      if (g < 0 || g == f) continue;
      for (int k = 0; k < 3; ++k)
        if (t.faceEdges[3 * g + k] == e) twin[3 * f + c] = 3 * g + k;
    }
  return twin;
}

VertexFaces vertexFaces(const SurfaceMesh& mesh, int32_t numVertices) {
  const std::vector<int32_t>& T = mesh.triangles;
  VertexFaces out;
  out.start.assign(static_cast<size_t>(numVertices) + 1, 0);
  for (const int32_t v : T) ++out.start[v + 1];
  for (int32_t v = 0; v < numVertices; ++v) out.start[v + 1] += out.start[v];
  out.faces.resize(T.size());
  std::vector<int32_t> fill(out.start.begin(), out.start.end() - 1);
  for (size_t corner = 0; corner < T.size(); ++corner)
    out.faces[fill[T[corner]]++] = static_cast<int32_t>(corner / 3);
  return out;
}

std::vector<double> unitFaceNormals(const SurfaceMesh& mesh) {
  const int32_t nF = mesh.numFaces();
  std::vector<double> normals(3 * static_cast<size_t>(nF), 0.0);
  for (int32_t f = 0; f < nF; ++f) {
    const Eigen::Vector3d n = faceNormal(mesh, f);
    if (n.squaredNorm() == 0) {
      normals[3 * f + 2] = 1;
      continue;
    }
    for (int k = 0; k < 3; ++k) normals[3 * f + k] = n[k];
  }
  return normals;
}

}  // namespace tvf
