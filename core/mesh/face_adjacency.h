#pragma once
// A face's neighbours, as the page's picking and surface tracing walk them (web/geometry/mesh-bvh-transfer.js
// pickingParts): each corner's half-edge paired with its twin in the face across, and the faces round each
// vertex. Read off the topology the core already built, where the page derived them again from the triangles
// (262-331 ms under node at 832k faces, on the way to a big model's factorization; the core 83-129 ms).
#include <cstdint>
#include <vector>

#include "dec/hodge_star.h"
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

// The unit face normals the geometry holds (MeshGeometry::faceNormal), with (0, 0, 1) for a face of zero area
// where it has zero, as the page has it.
std::vector<double> pageFaceNormals(const MeshGeometry& geometry);

}  // namespace tvf
