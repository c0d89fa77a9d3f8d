#pragma once
// Boundary conditions of Sec. 4.1 resolved to per-edge angles.
#include <cstdint>
#include <vector>

#include "design/designer.h"
#include "mesh/mesh_topology.h"

namespace tvf {

// beta per edge for fixed-angle conditions (NaN on interior edges); empty for free boundaries.
std::vector<double> boundaryEdgeAngles(const MeshTopology& topology, const BoundaryCondition& bc);

}  // namespace tvf
