#pragma once
// What a signed consumer (a flow map, a tangent frame, a texture synthesizer, a bilinear texture lookup)
// needs of an N-direction field: one of the N directions chosen per face so that neighbours agree. Within
// each chart of a UV atlas (faces joined across edges whose corners keep their UVs) the choice spreads over a
// spanning tree grown best-aligned first, so the lines where it cannot agree — forced by singularities of
// fractional index — fall where the field turns most, and chart seams cost nothing.
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct CombedDirections {
  std::vector<double> face;    // 3 per face, unit: one of the N representatives
  std::vector<double> corner;  // 9 per face: each corner's vertex representative turned closest to `face`
  int32_t flippedEdges = 0;    // interior edges inside a chart across which the combed directions disagree
};

// faceDirections: one unit representative per face (a Designer's faceVectors() for symmetry N). cornerUVs: 6
// per face, or empty (then each connected component is one chart).
CombedDirections combDirections(const SurfaceMesh& mesh, const MeshTopology& topology,
                                const MeshGeometry& geometry, const std::vector<double>& faceDirections,
                                int symmetry, const std::vector<float>& cornerUVs);

// One of the N directions per vertex, chosen so that neighbours agree: vertexDirections (3 per vertex, unit
// representatives, zero where the field is) turned by multiples of 2 pi / N about each vertex's normal along
// a spanning tree of the edges grown best-aligned first from each component's first vertex, so that the edges
// across which they cannot agree (forced round singularities of fractional index) gather where the field
// turns most. A cross field's stripe families (direction/stripe_pattern.h) follow these: a brick or weave
// swaps its rows and columns only across such edges.
// normals: 3 per vertex, unit (vertexNormals).
std::vector<double> combVertexDirections(const MeshTopology& topology, const std::vector<double>& normals,
                                         const std::vector<double>& vertexDirections, int symmetry);

// The interior edges across which the vertex directions (3 per vertex) do not agree: where, turned into the
// plane of one of the edge's faces, the second is nearer a turn of 2 pi / N than the first.
int32_t disagreeingEdges(const MeshTopology& topology, const std::vector<double>& normals,
                         const std::vector<double>& vertexDirections, int symmetry);

// The corner directions interpolated at a barycentric point of face f and normalised.
Eigen::Vector3d combedDirection(const CombedDirections& combed, int32_t f, const double bary[3]);

}  // namespace tvf
