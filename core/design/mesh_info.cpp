#include "design/mesh_info.h"

#include "design/designer.h"
#include "mesh/mesh_checks.h"

namespace tvf {

nlohmann::json meshInfoJson(const SurfaceMesh& mesh) {
  const MeshReport report = checkMesh(mesh);
  nlohmann::json info = meshInfoJson(mesh, report.problems, report.topology ? &*report.topology : nullptr);
  if (info["usable"] && report.topology) {
    const MeshGeometry geometry = computeMeshGeometry(mesh, *report.topology);
    info["folds"] = foldsJson(foldProfile(mesh, *report.topology, geometry));
  }
  return info;
}

nlohmann::json meshInfoJson(const Designer& d) {
  nlohmann::json info = meshInfoJson(d.mesh(), d.meshNotes(), &d.topology());
  info["folds"] = foldsJson(d.foldProfile());
  return info;
}

nlohmann::json foldsJson(const FoldProfile& p) {
  return {{"interiorEdges", p.interiorEdges},
          {"gradualEdges", p.gradualEdges},
          {"sharpEdges", p.sharpEdges},
          {"longCurveEdges", p.longCurveEdges},
          {"sharpShare", p.sharpShare()},
          {"longCurveShare", p.longCurveShare()},
          {"suggestedFeatureAngle", suggestedFeatureAngle(p)}};
}

nlohmann::json meshInfoJson(const SurfaceMesh& mesh, const std::vector<MeshProblem>& problems,
                            const MeshTopology* topology) {
  nlohmann::json info;
  info["vertices"] = mesh.numVertices();
  info["faces"] = mesh.numFaces();
  info["hasUVs"] = mesh.hasUVs();
  nlohmann::json messages = nlohmann::json::array();
  bool usable = true;
  for (const auto& p : problems) {
    messages.push_back(p.message);
    usable = usable && !p.fatal;
  }
  info["problems"] = messages;
  info["usable"] = usable;
  if (!topology) return info;
  const MeshTopology& t = *topology;
  info["edges"] = t.numEdges;
  info["components"] = t.components.size();
  info["boundaryLoops"] = t.boundaryLoops.size();
  info["eulerCharacteristic"] = t.eulerCharacteristic();
  int32_t genus = 0, betti1 = 0;
  nlohmann::json perComponent = nlohmann::json::array();
  for (const auto& c : t.components) {
    genus += c.genus;
    betti1 += 2 * c.genus + std::max(0, c.boundaryLoops - 1);
    perComponent.push_back({{"vertices", c.vertices},
                            {"edges", c.edges},
                            {"faces", c.faces},
                            {"boundaryLoops", c.boundaryLoops},
                            {"eulerCharacteristic", c.eulerCharacteristic},
                            {"genus", c.genus}});
  }
  info["genus"] = genus;  // the sum over components; see perComponent when there are several
  info["firstBettiNumber"] = betti1;
  if (t.components.size() > 1) info["perComponent"] = perComponent;
  return info;
}

}  // namespace tvf
