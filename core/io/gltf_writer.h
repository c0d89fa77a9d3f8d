#pragma once
// GLB with a designed field (docs/export.md): per-vertex TANGENT along the field and a _FIELD attribute, a
// KHR_materials_anisotropy material, optional flow map / base colour images, and the design in extras.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "io/gltf_source.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// The extras key under which the design document and the flow map's texture index are stored.
inline constexpr const char* kGlbExtrasKey = "tangentFieldDesigner";

struct FieldGlbContent {
  const SurfaceMesh* mesh = nullptr;  // the welded mesh the field lives on
  // The document the mesh came from (attributes, materials and vertex layout kept), or null: then a new
  // document is built from the mesh, with cornerUVs (when not empty) as TEXCOORD_0 and a vertex per (welded
  // vertex, UV) pair: vertices split only at UV seams, so every chart imports as one connected surface.
  const GltfSource* source = nullptr;
  std::vector<float> cornerUVs;  // 6 per face; only read when source is null
  // 6 per face, a stripe pattern's phase (direction/stripe_texture.h stripeTexcoords) as a texture
  // coordinate: TEXCOORD_1 of a new document, the first free TEXCOORD_n of each kept primitive (its vertices
  // split where the phase differs: io/gltf_vertex_split.h), named in the primitive's extras
  // (stripePhaseTexCoord).
  std::vector<float> cornerTexcoord1;
  std::vector<double> vertexField;     // 3 per welded vertex, world space
  std::vector<double> vertexTangent;   // 3 per welded vertex, unit, in the tangent plane
  std::vector<double> vertexNormal;    // 3 per welded vertex, unit (used when source is null)
  std::vector<uint8_t> anisotropyPng;  // direction in the UV tangent frame, for normal-mapped materials
};

struct FieldGlbOptions {
  double anisotropyStrength = 1.0;
  double anisotropyRotation = 0.0;    // radians, counter-clockwise from the tangent
  std::vector<uint8_t> flowMapPng;    // embedded (and named in extras) when not empty
  std::vector<uint8_t> baseColorPng;  // e.g. a synthesized texture over the same UVs; base colour when set
  nlohmann::json design;              // stored in extras when not null
};

// True when some material that a triangle primitive uses has a normal map: then its tangent frame is kept
// and the direction goes into anisotropyTexture (FieldGlbContent::anisotropyPng).
bool sourceHasNormalMappedMaterial(const GltfSource& source);

std::vector<uint8_t> writeFieldGlb(const FieldGlbContent& content, const FieldGlbOptions& options);

// The design stored by writeFieldGlb in a GLB or glTF JSON, or null when there is none.
nlohmann::json readEmbeddedDesign(const uint8_t* data, std::size_t size);

}  // namespace tvf
