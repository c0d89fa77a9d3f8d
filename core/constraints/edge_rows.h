#pragma once
// Constraints that fix edge values (Sec. 4): each yields rows c_e = value with a single nonzero, so each is a
// rank-1 change of the factored matrix.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "constraints/constraint_spec.h"
#include "constraints/surface_walk.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct EdgeRow {
  int32_t edge;
  double value;  // target line integral along the edge's canonical orientation
};

// c_e = u . p_e on the face's three edges, with u projected into the face's plane.
std::vector<EdgeRow> vectorRows(const SurfaceMesh& mesh, const MeshTopology& topology, int32_t face,
                                const Eigen::Vector3d& u);

// Walks the surface between consecutive points and emits c_e = t . p_e for every crossed edge, t the unit
// tangent of the walk where it crosses. A stroke that stays inside one face becomes a vector constraint
// there.
std::vector<EdgeRow> strokeRows(const SurfaceMesh& mesh, const MeshTopology& topology,
                                const std::vector<SurfacePoint>& points);



}  // namespace tvf
