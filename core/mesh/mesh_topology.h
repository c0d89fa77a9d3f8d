#pragma once
// Combinatorics of a triangle mesh: canonically oriented edges, signed face-edge incidence, boundary loops
// and connected components. Built only from indices that are known to be in range (see mesh_checks).
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"

namespace tvf {

struct ComponentInfo {
  int32_t vertices = 0, edges = 0, faces = 0, boundaryLoops = 0;
  int32_t eulerCharacteristic = 0, genus = 0;
};

struct MeshTopology {
  int32_t numVertices = 0, numEdges = 0, numFaces = 0;
  std::vector<int32_t> edgeVertices;  // 2 per edge, lower vertex index first (the canonical orientation)
  // Per face corner c of face (v0, v1, v2): the edge from v_c to v_{c+1} and +1/-1 as the face's traversal
  // agrees/disagrees with that edge's canonical orientation. These are the rows of d1.
  std::vector<int32_t> faceEdges;
  std::vector<int8_t> faceEdgeSigns;
  // Up to two faces per edge; -1 where there is none (boundary). Edges with more faces are non-manifold
  // and make the mesh unusable; edgeFaceCount records the true count for the checks.
  std::vector<int32_t> edgeFaces;
  std::vector<int32_t> edgeFaceCount;
  std::vector<uint8_t> isBoundaryEdge, isBoundaryVertex;
  std::vector<int32_t> vertexFaceCount;                  // 0 for vertices no face uses
  std::vector<int32_t> vertexEdgeStart, vertexEdgeList;  // CSR: edges incident to each vertex
  // Each loop is its boundary edges in walking order (following the faces' orientation).
  std::vector<std::vector<int32_t>> boundaryLoops;
  std::vector<int32_t> faceComponent, edgeComponent, vertexComponent;  // -1 for unused vertices
  std::vector<ComponentInfo> components;

  int32_t edgeOf(int32_t face, int32_t corner) const { return faceEdges[3 * face + corner]; }
  int32_t signOf(int32_t face, int32_t corner) const { return faceEdgeSigns[3 * face + corner]; }
  // The face across edge e from face f: -1 on a boundary edge; on a non-manifold edge only one of the others.
  int32_t otherFace(int32_t e, int32_t f) const {
    return edgeFaces[2 * e] == f ? edgeFaces[2 * e + 1] : edgeFaces[2 * e];
  }
  int32_t eulerCharacteristic() const;
};

// Requires every index in [0, numVertices). Boundary loops are traced only where vertices are manifold.
MeshTopology buildTopology(const SurfaceMesh& mesh);

// The edge joining two vertices, or -1.
int32_t findEdge(const MeshTopology& topology, int32_t a, int32_t b);

}  // namespace tvf
