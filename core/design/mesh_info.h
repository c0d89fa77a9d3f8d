#pragma once
// The `tvf info` report: counts, topology per component, and every problem found.
#include <nlohmann/json.hpp>

#include "mesh/surface_mesh.h"

namespace tvf {

// Never throws for a mesh that parsed; problems are listed (fatal ones make `usable` false).
nlohmann::json meshInfoJson(const SurfaceMesh& mesh);

}  // namespace tvf
