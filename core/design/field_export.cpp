#include "design/field_export.h"

#include <algorithm>

#include "direction/combing.h"
#include "field/field_tangents.h"
#include "field/whitney_reconstruction.h"
#include "io/gltf_writer.h"
#include "io/png_writer.h"
#include "io/raw_field.h"
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

FieldComponent fieldComponentFromName(const std::string& name) {
  for (const FieldComponent c :
       {FieldComponent::Whole, FieldComponent::Exact, FieldComponent::Coexact, FieldComponent::Harmonic})
    if (name == fieldComponentName(c)) return c;
  throw InputError("unknown component \"" + name + "\" (whole, exact, coexact or harmonic)");
}

const char* fieldComponentName(FieldComponent component) {
  switch (component) {
    case FieldComponent::Exact:
      return "exact";
    case FieldComponent::Coexact:
      return "coexact";
    case FieldComponent::Harmonic:
      return "harmonic";
    case FieldComponent::Whole:
      break;
  }
  return "whole";
}

std::vector<double> componentOneForm(const HodgeDecomposition& h, FieldComponent component) {
  const Eigen::VectorXd part = component == FieldComponent::Exact     ? h.exact
                               : component == FieldComponent::Coexact ? h.coexact
                               : component == FieldComponent::Harmonic
                                   ? h.harmonic
                                   : Eigen::VectorXd(h.exact + h.coexact + h.harmonic);
  return std::vector<double>(part.data(), part.data() + part.size());
}

nlohmann::json hodgeDocument(const HodgeDecomposition& h) {
  const auto list = [](const Eigen::VectorXd& x) {
    return std::vector<double>(x.data(), x.data() + x.size());
  };
  const HodgeEnergyShares shares = hodgeEnergyShares(h);
  return {
      {"exact", list(h.exact)},
      {"coexact", list(h.coexact)},
      {"harmonic", list(h.harmonic)},
      {"potential0", list(h.potential0)},
      {"potential2", list(h.potential2)},
      {"energyShares", {{"exact", shares.exact}, {"coexact", shares.coexact}, {"harmonic", shares.harmonic}}},
      {"metric", h.metricName},
      {"decomposeMs", h.milliseconds}};
}

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

namespace {

// The GLB of any field: its vertex values (the _FIELD attribute and the tangent frames) and its value inside
// faces (the flow map and the anisotropy texture of normal-mapped materials).
std::vector<uint8_t> fieldGlb(const SurfaceMesh& mesh, const MeshTopology& topology, const GltfSource* source,
                              const ExportAtlas& atlas, std::vector<double> vertexField,
                              const FaceFieldSampler& sample, const nlohmann::json& design,
                              const FieldExportOptions& options, const std::vector<uint8_t>& baseColorPng,
                              const std::vector<float>& phaseTexcoords) {
  const std::vector<float>& cornerUVs = atlas.cornerUVs;
  // A generated atlas cuts the surface where the source's vertices do not: only a new layout can hold it.
  if (atlas.generated) source = nullptr;
  FieldGlbContent content;
  content.mesh = &mesh;
  content.source = source;
  content.cornerUVs = source ? std::vector<float>{} : cornerUVs;
  content.cornerTexcoord1 = phaseTexcoords;
  content.vertexField = std::move(vertexField);
  content.vertexNormal = vertexNormals(mesh);
  content.vertexTangent = fieldTangents(mesh, content.vertexNormal, content.vertexField);
  if (source && sourceHasNormalMappedMaterial(*source)) {
    if (cornerUVs.empty()) {
      throw InputError("the model has a normal map but no usable texture coordinates for anisotropyTexture");
    }
    const FlowField frame = rasterizeFlowField(mesh, topology, cornerUVs.data(), sample, options.size,
                                               options.gutterTexels, FlowFrame::UvTangent);
    content.anisotropyPng =
        encodePngRgba(encodeFlowMap(frame, FlowMapConvention::Gltf, 8), options.size, options.size, 8);
  }
  FieldGlbOptions glb;
  glb.anisotropyStrength = options.anisotropyStrength;
  glb.anisotropyRotation = options.anisotropyRotation;
  glb.baseColorPng = baseColorPng;
  if (options.embedFlowMap && !cornerUVs.empty()) {
    requireUnitSquareUVs(cornerUVs, mesh.numFaces());
    const FlowField field =
        rasterizeFlowField(mesh, topology, cornerUVs.data(), sample, options.size, options.gutterTexels);
    glb.flowMapPng = encodePngRgba(encodeFlowMap(field, options.convention, options.bits), options.size,
                                   options.size, options.bits);
  }
  if (options.embedDesign) glb.design = design;
  return writeFieldGlb(content, glb);
}

// The combed field's vertex values: each vertex's corners summed (they agree within a chart away from the
// flip lines), or its own representative where they cancel.
std::vector<double> combedVertexField(const SurfaceMesh& mesh, const CombedDirections& combed) {
  std::vector<double> out(mesh.positions.size(), 0.0);
  for (int32_t f = 0; f < mesh.numFaces(); ++f)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) out[3 * mesh.triangles[3 * f + c] + k] += combed.corner[9 * f + 3 * c + k];
  for (size_t v = 0; 3 * v < out.size(); ++v) {
    Eigen::Map<Eigen::Vector3d> u(&out[3 * v]);
    if (u.norm() > 1e-6) u.normalize();
  }
  return out;
}

void requireDirectionsOn(const MeshTopology& topology, const std::vector<double>& faceDirections,
                         int symmetry) {
  if (symmetry < 1 || symmetry > 6) throw InputError("direction exports need a symmetry from 1 to 6");
  if (faceDirections.size() != 3 * static_cast<std::size_t>(topology.numFaces))
    throw InputError("the field has " + std::to_string(faceDirections.size() / 3) +
                     " directions, the mesh has " + std::to_string(topology.numFaces) + " faces");
}

}  // namespace

std::vector<uint8_t> exportFieldGlb(const SurfaceMesh& mesh, const MeshTopology& topology,
                                    const MeshGeometry& geometry, const GltfSource* source,
                                    const ExportAtlas& atlas, const std::vector<double>& oneForm,
                                    const nlohmann::json& design, const FieldExportOptions& options,
                                    const std::vector<uint8_t>& baseColorPng,
                                    const std::vector<float>& phaseTexcoords) {
  requireOneFormOn(topology, oneForm);
  std::vector<double> vertexField;
  vertexVectors(mesh, topology, geometry, oneForm.data(), vertexField);
  const FaceFieldSampler whitney = [&](int32_t f, const double bary[3]) {
    return whitneyVector(mesh, topology, oneForm.data(), f, bary);
  };
  return fieldGlb(mesh, topology, source, atlas, std::move(vertexField), whitney, design, options,
                  baseColorPng, phaseTexcoords);
}

std::vector<uint8_t> exportDirectionFlowMapPng(const SurfaceMesh& mesh, const MeshTopology& topology,
                                               const MeshGeometry& geometry,
                                               const std::vector<float>& cornerUVs,
                                               const std::vector<double>& faceDirections, int symmetry,
                                               const FieldExportOptions& options) {
  requireUnitSquareUVs(cornerUVs, mesh.numFaces());
  requireDirectionsOn(topology, faceDirections, symmetry);
  const CombedDirections combed =
      combDirections(mesh, topology, geometry, faceDirections, symmetry, cornerUVs);
  const FaceFieldSampler sample = [&](int32_t f, const double bary[3]) {
    return combedDirection(combed, f, bary);
  };
  const FlowField field =
      rasterizeFlowField(mesh, topology, cornerUVs.data(), sample, options.size, options.gutterTexels);
  return encodePngRgba(encodeFlowMap(field, options.convention, options.bits), options.size, options.size,
                       options.bits);
}

std::vector<uint8_t> exportDirectionGlb(const SurfaceMesh& mesh, const MeshTopology& topology,
                                        const MeshGeometry& geometry, const GltfSource* source,
                                        const ExportAtlas& atlas, const std::vector<double>& faceDirections,
                                        int symmetry, const nlohmann::json& design,
                                        const FieldExportOptions& options,
                                        const std::vector<uint8_t>& baseColorPng,
                                        const std::vector<float>& phaseTexcoords) {
  requireDirectionsOn(topology, faceDirections, symmetry);
  const CombedDirections combed =
      combDirections(mesh, topology, geometry, faceDirections, symmetry, atlas.cornerUVs);
  const FaceFieldSampler sample = [&](int32_t f, const double bary[3]) {
    return combedDirection(combed, f, bary);
  };
  return fieldGlb(mesh, topology, source, atlas, combedVertexField(mesh, combed), sample, design, options,
                  baseColorPng, phaseTexcoords);
}

std::string exportRawField(const MeshGeometry& geometry, const std::vector<double>& faceDirections,
                           int symmetry) {
  return writeRawField(faceDirections, geometry.faceNormal, symmetry);
}

}  // namespace tvf
