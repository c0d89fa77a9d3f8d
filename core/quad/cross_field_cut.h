#pragma once
// What a seamless parametrization needs of a cross field before it is solved: the field combed over a
// spanning tree of the faces, the matching (quarter turns) across every edge, the cones (vertices round
// which the matchings do not add up to a whole turn: the field's +-1/4 singularities), and a cut graph
// through the cones and round the handles that leaves a disc, the mesh's vertices split along it into
// copies, one per side.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct CrossFieldCut {
  std::vector<double> direction;  // 3 per face: the combed representative X (unit, in the face's plane)
  // Per interior edge, from edgeFaces[2e] (f) to edgeFaces[2e + 1] (g): X_g is f's X carried across the edge
  // and turned r quarters counter-clockwise about g's normal, r in 0..3. 0 on boundary edges.
  std::vector<int8_t> matching;
  std::vector<uint8_t> cut;  // per edge: 1 on the cut graph
  // Copies: a vertex has one per side of the cut round it (one where no cut edge meets it). Each fan of faces
  // round a vertex is walked counter-clockwise; a copy's faces follow the one before it across a cut edge.
  std::vector<int32_t> cornerCopy;  // 3 per face
  std::vector<int32_t> copyFan;     // per copy: its fan (a vertex's cycle of faces)
  std::vector<int32_t> copyEdge;    // per copy: the cut edge crossed into it from the copy before (-1: none)
  std::vector<int32_t> copyFromFace;  // per copy: the face on the far side of that edge (the copy before)
  std::vector<int32_t> copyPrevious;  // per copy: the copy before it in its fan (itself when it is alone)
  std::vector<int32_t> fanFirstCopy;  // fans + 1 (CSR over copies, which are numbered fan by fan)
  std::vector<int8_t> fanTurns;       // per fan: the matchings round it, mod 4 (0: regular, else a cone)
  std::vector<int32_t> fanVertex;     // per fan
  std::vector<int32_t> fanFaceStart, fanFaceList;  // CSR: each fan's faces, counter-clockwise
  int32_t cones = 0;
  int32_t cutEdges = 0;
  // The edges that must lie on an integer iso-line (the boundary's, and the features'): per such edge, the
  // face beside it whose chart says so (the first) and the coordinate (0: u, 1: v) constant along it there,
  // the one of the combed field's two directions farther from the edge's.
  struct IsoEdge {
    int32_t edge, face;
    int8_t coordinate;
  };
  std::vector<IsoEdge> isoEdges;
};

// faceDirections: 3 per face, any one of the cross field's four directions (zero where the field vanishes).
// featureEdges: edges (indices) the quads' edges are to follow, besides the boundary's.
CrossFieldCut cutCrossField(const SurfaceMesh& mesh, const MeshTopology& topology,
                            const MeshGeometry& geometry, const std::vector<double>& faceDirections,
                            const std::vector<int32_t>& featureEdges = {});

// X turned `quarters` times counter-clockwise about the unit normal n (in n's plane).
Eigen::Vector3d quarterTurned(const Eigen::Vector3d& x, const Eigen::Vector3d& n, int quarters);

}  // namespace tvf
