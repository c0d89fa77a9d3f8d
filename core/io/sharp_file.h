#pragma once
// QuadWild's feature edges (.sharp; Pietroni et al., read by LoadSharpFeatures in
// components/field_computation/triangle_mesh_type.h and written there by SaveSharpFeatures): a line with the
// entry count, then one line "type,face,corner" per face side on a feature, where the side is the face's edge
// from its corner `corner` to corner `corner + 1` and type is 0 for a concave fold, 1 for a convex one.
#include <cstdint>
#include <string>
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"

namespace tvf {

// One entry per face side along `featureEdges` (edge indices), both faces of an interior edge, and every
// boundary edge as convex: what QuadWild writes itself (its sharp-feature set marks the border so), in its
// order (by face, then corner). An interior edge is convex when (n0 x n1) . (p1 - p0) >= 0, with n0 the
// normal of a face whose side runs from p0 to p1 and n1 the other face's: QuadWild's IsConcaveEdge with its
// limit 0.
std::string writeSharpFile(const MeshTopology& topology, const MeshGeometry& geometry,
                           const std::vector<double>& positions, const std::vector<int32_t>& featureEdges);

}  // namespace tvf
