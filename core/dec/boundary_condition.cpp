#include "dec/boundary_condition.h"

#include <cmath>
#include <string>

#include "common/input_error.h"

namespace tvf {

BoundaryCondition BoundaryCondition::tangential() {
  return fixedAngle(M_PI / 2);
}

bool sameBoundaryCondition(const BoundaryCondition& a, const BoundaryCondition& b) {
  if (a.free != b.free) return false;
  if (a.free) return true;
  if (a.angle != b.angle || a.perEdge.size() != b.perEdge.size()) return false;
  for (size_t k = 0; k < a.perEdge.size(); ++k)
    if (a.perEdge[k].i != b.perEdge[k].i || a.perEdge[k].j != b.perEdge[k].j ||
        a.perEdge[k].angle != b.perEdge[k].angle)
      return false;
  return true;
}

std::vector<double> boundaryEdgeAngles(const MeshTopology& t, const BoundaryCondition& bc) {
  if (bc.free) return {};
  std::vector<double> angles(t.numEdges, std::nan(""));
  for (int32_t e = 0; e < t.numEdges; ++e)
    if (t.isBoundaryEdge[e]) angles[e] = bc.angle;
  for (const auto& o : bc.perEdge) {
    const int32_t e = findEdge(t, o.i, o.j);
    if (e < 0 || !t.isBoundaryEdge[e])
      throw InputError("boundary override (" + std::to_string(o.i) + ", " + std::to_string(o.j) +
                       ") is not a boundary edge of the mesh");
    if (!std::isfinite(o.angle))
      throw InputError("boundary override (" + std::to_string(o.i) + ", " + std::to_string(o.j) +
                       ") has a non-finite angle");
    angles[e] = o.angle;
  }
  return angles;
}

}  // namespace tvf
