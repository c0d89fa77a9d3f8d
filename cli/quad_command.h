#pragma once
// tvf quad MESH DESIGN -o OUT.obj [--edge-length L | --quads N] [--json]: the design's cross field to a quad
// mesh (core/quad/quad_remesh.h), written as OBJ, its statistics printed.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace tvf::cli {

// readDesign: DESIGN.json or an exported GLB's embedded design, as the other commands read it.
int quadCommand(int argc, char** argv, const std::function<nlohmann::json(const std::string&)>& readDesign);

// tvf bench MESH --quads N [--repeat R]: the smoothest cross field of MESH remeshed to about N quads R
// times; medians of the times (ms) and the last run's statistics, as JSON.
nlohmann::json quadBench(const std::string& meshPath, int64_t quads, int repeat);

}  // namespace tvf::cli
