#pragma once
// Boundary conditions of Sec. 4.1 and their resolution to per-edge angles.
#include <cstdint>
#include <vector>

#include "mesh/mesh_topology.h"

namespace tvf {

// "free", or a fixed angle beta per boundary edge (tangential = pi/2, normal = 0), with optional overrides.
struct BoundaryCondition {
  bool free = true;
  double angle = 0.0;  // used when !free
  struct EdgeAngle {
    int32_t i, j;
    double angle;
  };
  std::vector<EdgeAngle> perEdge;  // overrides, vertex pairs in any order

  static BoundaryCondition makeFree() { return {}; }
  static BoundaryCondition fixedAngle(double beta) { return {false, beta, {}}; }
  static BoundaryCondition tangential();
  static BoundaryCondition normal() { return fixedAngle(0.0); }
};

// The same condition, overrides in the same order (re-applying a design must not refactor).
bool sameBoundaryCondition(const BoundaryCondition& a, const BoundaryCondition& b);

// beta per edge for fixed-angle conditions (NaN on interior edges); empty for free boundaries. Throws
// InputError for an override that is not a boundary edge or has a non-finite angle.
std::vector<double> boundaryEdgeAngles(const MeshTopology& topology, const BoundaryCondition& bc);

}  // namespace tvf
