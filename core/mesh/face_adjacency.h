#pragma once
// A face's neighbours, as the page's picking and surface tracing walk them (web/geometry/mesh-bvh-transfer.js
// pickingParts): each corner's half-edge paired with its twin in the face across, and the faces round each
// vertex. Read off the topology the core already built, where the page derived them again from the triangles
// (262-331 ms under node at 832k faces, on the way to a big model's factorization; the core 99-126 ms).
#include <cstdint>
#include <vector>

#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// twin[3f + c] = 3g + c' where the half-edge from corner c of face f (v_c to v_{c+1}) is the one from corner
// c' of face g; -1 on a boundary edge.
std::vector<int32_t> halfEdgeTwins(const MeshTopology& topology);

// CSR of the faces round each vertex: faces[start[v] .. start[v + 1]) in increasing face order.
struct VertexFaces {
  std::vector<int32_t> start, faces;
};
VertexFaces vertexFaces(const SurfaceMesh& mesh, int32_t numVertices);

// Unit face normals, 3 per face, from the faces' winding; (0, 0, 1) for a face of zero area, as the page has
// it (faceNormal gives zero there).
std::vector<double> unitFaceNormals(const SurfaceMesh& mesh);

}  // namespace tvf
