#pragma once
// tvf quad MESH DESIGN -o OUT.obj [--edge-length L | --quads N] [--json]: the design's cross field to a quad
// mesh (core/quad/quad_remesh.h), written as OBJ, its statistics printed.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace tvf::cli {

// readDesign: DESIGN.json or an exported GLB's embedded design, as the other commands read it.
int quadCommand(int argc, char** argv, const std::function<nlohmann::json(const std::string&)>& readDesign);

}  // namespace tvf::cli
