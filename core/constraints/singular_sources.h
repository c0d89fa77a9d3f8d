#pragma once
// Sources, sinks and vortices as right-hand sides (Sec. 3.1): a divergence target s per vertex and a curl
// target r per face, projected to zero mean on closed components, where anything produced must be consumed.
#include <Eigen/Core>
#include <vector>

#include "constraints/constraint_spec.h"
#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"

namespace tvf {

struct SourceTargets {
  Eigen::VectorXd divergence;  // s_v: -flux/|v*| at a source (delta = -div), +flux/|v*| at a sink
  Eigen::VectorXd curl;        // r_t: circulation around the face, + with its orientation
};

SourceTargets singularTargets(const MeshTopology& topology, const MeshGeometry& geometry,
                              const std::vector<ConstraintSpec>& sources,
                              const std::vector<ConstraintSpec>& sinks,
                              const std::vector<ConstraintSpec>& vortices);

}  // namespace tvf
