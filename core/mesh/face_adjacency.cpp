#include "mesh/face_adjacency.h"

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

std::vector<double> pageFaceNormals(const MeshGeometry& geometry) {
  std::vector<double> normals = geometry.faceNormal;
  for (size_t f = 0; f < normals.size(); f += 3)
    if (normals[f] == 0 && normals[f + 1] == 0 && normals[f + 2] == 0) normals[f + 2] = 1;
  return normals;
}

}  // namespace tvf
