#pragma once
// Sharp features: the interior edges where the surface folds by more than a threshold (the angle between
// the two faces' normals, 0 for a flat pair), plus the user's additions and minus the user's removals.
#include <array>
#include <cstdint>
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"

namespace tvf {

using VertexPair = std::array<int32_t, 2>;

// Interior edges whose normals differ by more than `degrees` (0: none), ascending.
std::vector<int32_t> sharpEdges(const MeshTopology& topology, const MeshGeometry& geometry, double degrees);

// sharpEdges(degrees), plus `add`, minus `remove`, ascending and without repeats. Throws InputError naming a
// pair that is not a mesh edge (or is a boundary edge: the boundary condition owns those), or an angle that is
// not a number in [0, 180].
std::vector<int32_t> featureEdges(const MeshTopology& topology, const MeshGeometry& geometry, double degrees,
                                  const std::vector<VertexPair>& add, const std::vector<VertexPair>& remove);

// Feature curves: maximal chains of feature edges through vertices where exactly two feature edges meet
// (a closed loop is one curve). Each curve's edges in walking order, with +1 where the walk runs along the
// edge's canonical orientation (lower vertex first) and -1 against it: the orientation a vector field
// (N = 1) follows along the curve.
struct FeatureCurve {
  std::vector<int32_t> edges;
  std::vector<int8_t> signs;
  bool closed = false;
};
std::vector<FeatureCurve> featureCurves(const MeshTopology& topology, const std::vector<int32_t>& edges);

}  // namespace tvf
