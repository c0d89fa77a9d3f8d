#include "constraints/singular_sources.h"

namespace tvf {

SourceTargets singularTargets(const MeshTopology& t, const MeshGeometry& g,
                              const std::vector<ConstraintSpec>& sources,
                              const std::vector<ConstraintSpec>& sinks,
                              const std::vector<ConstraintSpec>& vortices) {
  SourceTargets out{Eigen::VectorXd::Zero(t.numVertices), Eigen::VectorXd::Zero(t.numFaces)};
  for (const auto& s : sources) out.divergence[s.element] -= s.strength / g.star0[s.element];
  for (const auto& s : sinks) out.divergence[s.element] += s.strength / g.star0[s.element];
  for (const auto& s : vortices) out.curl[s.element] += s.strength;
  // Zero-mean projections on closed components: area-weighted for s, proportional to |t| for r.
  const size_t nC = t.components.size();
  std::vector<double> divergenceTotal(nC, 0), vertexArea(nC, 0), curlTotal(nC, 0), faceArea(nC, 0);
  for (int32_t v = 0; v < t.numVertices; ++v) {
    const int32_t c = t.vertexComponent[v];
    if (c < 0) continue;
    divergenceTotal[c] += out.divergence[v] * g.star0[v];
    vertexArea[c] += g.star0[v];
  }
  for (int32_t f = 0; f < t.numFaces; ++f) {
    curlTotal[t.faceComponent[f]] += out.curl[f];
    faceArea[t.faceComponent[f]] += g.faceArea[f];
  }
  for (int32_t v = 0; v < t.numVertices; ++v) {
    const int32_t c = t.vertexComponent[v];
    if (c >= 0 && t.components[c].boundaryLoops == 0) out.divergence[v] -= divergenceTotal[c] / vertexArea[c];
  }
  for (int32_t f = 0; f < t.numFaces; ++f) {
    const int32_t c = t.faceComponent[f];
    if (t.components[c].boundaryLoops == 0) out.curl[f] -= g.faceArea[f] * curlTotal[c] / faceArea[c];
  }
  return out;
}

}  // namespace tvf
