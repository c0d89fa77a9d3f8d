#pragma once
// The quad remesher's options and statistics as JSON: one spelling for the CLI (tvf quad --json), the wasm
// binding and the page.
#include <nlohmann/json.hpp>
#include <string>

#include "quad/quad_remesh.h"

namespace tvf {

// {"edgeLength": L} or {"quads": N}, and "featureEdges": [a, b, a, b, ...] (vertex pairs, flat: the edges
// the quads' edges follow); anything else ignored. Throws InputError for a malformed text or a value of the
// wrong kind.
QuadRemeshOptions quadRemeshOptionsFromJson(const std::string& text);

// The statistics (quad_mesh_stats.h's names), the edge length used, how it went and the times (ms).
nlohmann::json quadRemeshJson(const QuadRemeshResult& result);

}  // namespace tvf
