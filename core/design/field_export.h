#pragma once
// What `tvf export` and the page's export buttons produce, computed once here for both: the flow map PNG
// and the GLB with the field (docs/export.md).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "field/flow_map.h"
#include "io/gltf_source.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct FieldExportOptions {
  int size = 1024;  // flow map texels per side
  FlowMapConvention convention = FlowMapConvention::Gltf;
  int bits = 8;
  int gutterTexels = 4;
  double anisotropyStrength = 1.0;
  double anisotropyRotation = 0.0;
  bool embedFlowMap = true;  // in the GLB, when UVs are available
  bool embedDesign = true;   // the design document in the GLB's extras
};

// The atlas the exports use: the mesh's own UVs when they are one (in [0,1]^2). Throws InputError naming
// the problem otherwise.
std::vector<float> exportAtlasUVs(const SurfaceMesh& mesh);

std::vector<uint8_t> exportFlowMapPng(const SurfaceMesh& mesh, const std::vector<float>& cornerUVs,
                                      const std::vector<double>& oneForm, const FieldExportOptions& options);

// source: the glTF the mesh was loaded from (kept as it was), or null. cornerUVs: the atlas for the flow
// map and (for non-glTF sources) TEXCOORD_0; may be empty (then no flow map). oneForm: per edge, canonical
// orientation. design: stored in extras when not null (and options.embedDesign).
std::vector<uint8_t> exportFieldGlb(const SurfaceMesh& mesh, const GltfSource* source,
                                    const std::vector<float>& cornerUVs, const std::vector<double>& oneForm,
                                    const nlohmann::json& design, const FieldExportOptions& options,
                                    const std::vector<uint8_t>& baseColorPng = {});

}  // namespace tvf
