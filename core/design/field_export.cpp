#include "design/field_export.h"

#include "dec/hodge_star.h"
#include "field/field_tangents.h"
#include "field/whitney_reconstruction.h"
#include "io/gltf_writer.h"
#include "io/png_writer.h"
#include "mesh/mesh_topology.h"

namespace tvf {

std::vector<float> exportAtlasUVs(const SurfaceMesh& mesh) {
  if (!mesh.hasUVs()) {
    // The atlas generator for UV-less models lives with texture synthesis and is not part of the core yet.
    throw InputError(
        "the model has no texture coordinates (TEXCOORD_0), so it has no atlas for a flow map; "
        "export a model with its own UVs");
  }
  checkAtlasUVs(mesh.cornerUVs, mesh.numFaces());
  return mesh.cornerUVs;
}

std::vector<uint8_t> exportFlowMapPng(const SurfaceMesh& mesh, const std::vector<float>& cornerUVs,
                                      const std::vector<double>& oneForm, const FieldExportOptions& options) {
  checkAtlasUVs(cornerUVs, mesh.numFaces());
  const MeshTopology topology = buildTopology(mesh);
  if (oneForm.size() != static_cast<std::size_t>(topology.numEdges)) {
    throw InputError("one-form has " + std::to_string(oneForm.size()) + " values, the mesh has " +
                     std::to_string(topology.numEdges) + " edges");
  }
  const FlowField field = rasterizeFlowField(mesh, topology, cornerUVs.data(), oneForm.data(), options.size,
                                             options.gutterTexels);
  return encodePngRgba(encodeFlowMap(field, options.convention, options.bits), options.size, options.size,
                       options.bits);
}

std::vector<uint8_t> exportFieldGlb(const SurfaceMesh& mesh, const GltfSource* source,
                                    const std::vector<float>& cornerUVs, const std::vector<double>& oneForm,
                                    const nlohmann::json& design, const FieldExportOptions& options,
                                    const std::vector<uint8_t>& baseColorPng) {
  const MeshTopology topology = buildTopology(mesh);
  if (oneForm.size() != static_cast<std::size_t>(topology.numEdges)) {
    throw InputError("one-form has " + std::to_string(oneForm.size()) + " values, the mesh has " +
                     std::to_string(topology.numEdges) + " edges");
  }
  FieldGlbContent content;
  content.mesh = &mesh;
  content.source = source;
  content.cornerUVs = source ? std::vector<float>{} : cornerUVs;
  vertexVectors(mesh, topology, computeMeshGeometry(mesh, topology), oneForm.data(), content.vertexField);
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
    glb.flowMapPng = exportFlowMapPng(mesh, cornerUVs, oneForm, options);
  if (options.embedDesign) glb.design = design;
  return writeFieldGlb(content, glb);
}

}  // namespace tvf
