#include "quad/quad_remesh_json.h"

#include <cstdint>

#include "common/input_error.h"

namespace tvf {

QuadRemeshOptions quadRemeshOptionsFromJson(const std::string& text) {
  nlohmann::json j;
  try {
    j = text.empty() ? nlohmann::json::object() : nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error&) {
    throw InputError("quad mesh options must be a JSON object");
  }
  if (!j.is_object()) throw InputError("quad mesh options must be a JSON object");
  QuadRemeshOptions o;
  if (j.contains("edgeLength")) {
    if (!j["edgeLength"].is_number()) throw InputError("quad mesh: edgeLength must be a number");
    o.edgeLength = j["edgeLength"].get<double>();
  }
  if (j.contains("quads")) {
    if (!j["quads"].is_number()) throw InputError("quad mesh: quads must be a number");
    const double n = j["quads"].get<double>();
    if (!(n >= 1) || !(n <= 4e6)) throw InputError("quad mesh: quads must be between 1 and 4 million");
    o.targetQuads = static_cast<int64_t>(n);
  }
  if (j.contains("featureEdges")) {
    const nlohmann::json& pairs = j["featureEdges"];
    if (!pairs.is_array()) throw InputError("quad mesh: featureEdges must be an array of vertex pairs");
    for (const nlohmann::json& v : pairs) {
      if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() > INT32_MAX)
        throw InputError("quad mesh: featureEdges must hold vertex indices");
      o.featureEdges.push_back(static_cast<int32_t>(v.get<int64_t>()));
    }
  }
  return o;
}

nlohmann::json quadRemeshJson(const QuadRemeshResult& r) {
  const QuadMeshStats& s = r.stats;
  return {{"faces", s.faces},
          {"quads", s.quads},
          {"vertices", s.vertices},
          {"edges", s.edges},
          {"quadShare", s.quadShare},
          {"irregularVertices", s.irregularVertices},
          {"valence3", s.valence3},
          {"valence5", s.valence5},
          {"fieldSingularities", s.fieldSingularities},
          {"irregularNearSingularity", s.irregularNearSingularity},
          {"irregularFarthest", s.irregularFarthest},
          {"crowdedSingularities", s.crowdedSingularities},
          {"edgeAngleMedianDeg", s.edgeAngleMedianDeg},
          {"edgeAngleP90Deg", s.edgeAngleP90Deg},
          {"hausdorffRelative", s.hausdorffRelative},
          {"aspectMedian", s.aspectMedian},
          {"flippedFaces", s.flippedFaces},
          {"degenerateFaces", s.degenerateFaces},
          {"boundaryEdges", s.boundaryEdges},
          {"manifold", s.manifold},
          {"oriented", s.oriented},
          {"eulerCharacteristic", s.eulerCharacteristic},
          {"edgeLength", r.edgeLength},
          {"cones", r.cones},
          {"cutEdges", r.cutEdges},
          {"flippedTriangles", r.flippedTriangles},
          {"integerUnknowns", r.integerUnknowns},
          {"roundingSolves", r.roundingSolves},
          {"unenforcedConditions", r.unenforcedConditions},
          {"stiffenings", r.stiffenings},
          {"featureCurves", r.featureCurves},
          {"releasedFeatureCurves", r.releasedFeatureCurves},
          {"failedTraces", r.failedTraces},
          {"openLoops", r.openLoops},
          {"filledHoles", r.filledHoles},
          {"splitPolygons", r.splitPolygons},
          {"ms", r.totalMs},
          {"stageMs",
           {{"cut", r.cutMs},
            {"parametrize", r.parametrizeMs},
            {"extract", r.extractMs},
            {"measure", r.measureMs}}}};
}

}  // namespace tvf
