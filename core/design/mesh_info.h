#pragma once
// The `tvf info` report: counts, topology per component, and every problem found.
#include <nlohmann/json.hpp>

#include "mesh/feature_edges.h"
#include "mesh/mesh_checks.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// Never throws for a mesh that parsed; problems are listed (fatal ones make `usable` false). A usable mesh's
// report has "folds" (foldsJson): how its edges fold, and the feature angle a new design starts at on it.
nlohmann::json meshInfoJson(const SurfaceMesh& mesh);
nlohmann::json foldsJson(const FoldProfile& profile);
// The same report from a check already made (a Designer keeps its own): checking again rebuilds the topology,
// 0.7 s of a scan's load at 1.25M edges.
// topology: null when the check could not build one.
nlohmann::json meshInfoJson(const SurfaceMesh& mesh, const std::vector<MeshProblem>& problems,
                            const MeshTopology* topology);
// A Designer's report, folds included, from what it derived when it was made (no second check).
class Designer;
nlohmann::json meshInfoJson(const Designer& designer);

}  // namespace tvf
