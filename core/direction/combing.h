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

// The corner directions interpolated at a barycentric point of face f and normalised.
Eigen::Vector3d combedDirection(const CombedDirections& combed, int32_t f, const double bary[3]);

}  // namespace tvf
