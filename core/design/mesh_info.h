#pragma once
// The `tvf info` report: counts, topology per component, and every problem found.
#include <nlohmann/json.hpp>

#include "mesh/mesh_checks.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// Never throws for a mesh that parsed; problems are listed (fatal ones make `usable` false).
nlohmann::json meshInfoJson(const SurfaceMesh& mesh);
// The same report from a check already made (a Designer keeps its own): checking again rebuilds the topology,
// 0.7 s of a scan's load at 1.25M edges.
// topology: null when the check could not build one.
nlohmann::json meshInfoJson(const SurfaceMesh& mesh, const std::vector<MeshProblem>& problems,
                            const MeshTopology* topology);

}  // namespace tvf
