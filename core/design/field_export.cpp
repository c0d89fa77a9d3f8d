#include "design/field_export.h"

#include <algorithm>

#include "field/field_tangents.h"
#include "field/whitney_reconstruction.h"
#include "io/gltf_writer.h"
#include "io/png_writer.h"
#include "mesh/mesh_geometry.h"
#include "texture/texture_atlas.h"

namespace tvf {

namespace {

void requireOneFormOn(const MeshTopology& topology, const std::vector<double>& oneForm) {
  if (oneForm.size() != static_cast<std::size_t>(topology.numEdges)) {
    throw InputError("one-form has " + std::to_string(oneForm.size()) + " values, the mesh has " +
                     std::to_string(topology.numEdges) + " edges");
  }
}

}  // namespace

ExportAtlas exportAtlas(const SurfaceMesh& mesh, const MeshTopology& topology,
                        const FieldExportOptions& options) {
  ExportAtlas atlas;
  if (mesh.hasUVs()) {
    // The overlap test rasterizes at this resolution; beyond 1024 it costs more than it tells.
    const AtlasCheck check =
        checkAtlasUVs(mesh.cornerUVs, mesh.numFaces(), std::clamp(options.size, 16, 1024));
    if (check.usable) {
      atlas.cornerUVs = mesh.cornerUVs;
      return atlas;
    }
    atlas.reason = "its TEXCOORD_0 is not a one-to-one atlas: " + check.reason;
  } else {
    atlas.reason = "it has no texture coordinates (TEXCOORD_0)";
  }
  const TextureAtlas generated = generateAtlas(mesh, topology, std::clamp(options.size, 16, 8192),
                                               std::clamp(options.gutterTexels, 0, 16));
  atlas.cornerUVs = generated.cornerUVs;
  atlas.generated = true;
  return atlas;
}

ExportAtlas exportAtlasFor(const SurfaceMesh& mesh, const MeshTopology& topology,
                           const FieldExportOptions& options, bool flowMap) {
  if (flowMap) return exportAtlas(mesh, topology, options);
  ExportAtlas none;
  if (!mesh.hasUVs()) return none;
  const AtlasCheck check = checkAtlasUVs(mesh.cornerUVs, mesh.numFaces(), std::clamp(options.size, 16, 1024));
  if (check.usable) none.cornerUVs = mesh.cornerUVs;
  return none;
}

std::vector<uint8_t> exportFlowMapPng(const SurfaceMesh& mesh, const MeshTopology& topology,
                                      const std::vector<float>& cornerUVs, const std::vector<double>& oneForm,
                                      const FieldExportOptions& options) {
  requireUnitSquareUVs(cornerUVs, mesh.numFaces());
  requireOneFormOn(topology, oneForm);
  const FlowField field = rasterizeFlowField(mesh, topology, cornerUVs.data(), oneForm.data(), options.size,
                                             options.gutterTexels);
  return encodePngRgba(encodeFlowMap(field, options.convention, options.bits), options.size, options.size,
                       options.bits);
}

std::vector<uint8_t> exportFieldGlb(const SurfaceMesh& mesh, const MeshTopology& topology,
                                    const MeshGeometry& geometry, const GltfSource* source,
                                    const ExportAtlas& atlas, const std::vector<double>& oneForm,
                                    const nlohmann::json& design, const FieldExportOptions& options,
                                    const std::vector<uint8_t>& baseColorPng) {
  requireOneFormOn(topology, oneForm);
  const std::vector<float>& cornerUVs = atlas.cornerUVs;
  // A generated atlas cuts the surface where the source's vertices do not: only a new layout can hold it.
  if (atlas.generated) source = nullptr;
  FieldGlbContent content;
  content.mesh = &mesh;
  content.source = source;
  content.cornerUVs = source ? std::vector<float>{} : cornerUVs;
  vertexVectors(mesh, topology, geometry, oneForm.data(), content.vertexField);
  content.vertexNormal = vertexNormals(mesh);
  content.vertexTangent = fieldTangents(mesh, content.vertexNormal, content.vertexField);
  if (source && sourceHasNormalMappedMaterial(*source)) {
    if (cornerUVs.empty()) {
      throw InputError("the model has a normal map but no usable texture coordinates for anisotropyTexture");
    }
    const FlowField frame = rasterizeFlowField(mesh, topology, cornerUVs.data(), oneForm.data(), options.size,
                                               options.gutterTexels, FlowFrame::UvTangent);
    content.anisotropyPng =
        encodePngRgba(encodeFlowMap(frame, FlowMapConvention::Gltf, 8), options.size, options.size, 8);
  }
  FieldGlbOptions glb;
  glb.anisotropyStrength = options.anisotropyStrength;
  glb.anisotropyRotation = options.anisotropyRotation;
  glb.baseColorPng = baseColorPng;
  if (options.embedFlowMap && !cornerUVs.empty())
    glb.flowMapPng = exportFlowMapPng(mesh, topology, cornerUVs, oneForm, options);
  if (options.embedDesign) glb.design = design;
  return writeFieldGlb(content, glb);
}

}  // namespace tvf
