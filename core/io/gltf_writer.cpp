#include "io/gltf_writer.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <tuple>

#include "io/gltf_vertex_split.h"

namespace tvf {
namespace {

using nlohmann::json;

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr const char* kAnisotropy = "KHR_materials_anisotropy";

// The new document's single buffer (the GLB's BIN chunk) and the JSON that indexes it.
class GlbBuilder {
 public:
  explicit GlbBuilder(json document) : doc_(std::move(document)) {}

  json& doc() { return doc_; }

  // Appends bytes (4-aligned, as every accessor's component type needs) and returns their offset.
  std::size_t append(const uint8_t* data, std::size_t size) {
    bin_.resize((bin_.size() + 3) / 4 * 4, 0);
    const std::size_t offset = bin_.size();
    bin_.insert(bin_.end(), data, data + size);
    return offset;
  }

  int addBufferView(const void* data, std::size_t size, int target) {
    const std::size_t offset = append(static_cast<const uint8_t*>(data), size);
    json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
    if (target) view["target"] = target;
    return push("bufferViews", view);
  }

  int addFloatAccessor(const std::vector<float>& values, int components, const char* type, bool bounds) {
    const std::size_t count = values.size() / components;
    json accessor = {{"bufferView", addBufferView(values.data(), values.size() * 4, kArrayBuffer)},
                     {"componentType", kFloat},
                     {"count", count},
                     {"type", type}};
    if (bounds) {
      std::vector<float> lo(components, std::numeric_limits<float>::max()), hi(components, -lo[0]);
      for (std::size_t i = 0; i < values.size(); ++i) {
        lo[i % components] = std::min(lo[i % components], values[i]);
        hi[i % components] = std::max(hi[i % components], values[i]);
      }
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    return push("accessors", accessor);
  }

  // A vertex attribute's elements, each on a 4-byte boundary as glTF asks (a stride where they are shorter).
  int addElementsAccessor(const AccessorElements& e, bool bounds) {
    const std::size_t stride = (e.elementSize + 3) / 4 * 4;
    std::vector<uint8_t> bytes(e.count * stride, 0);
    for (std::size_t i = 0; i < e.count; ++i)
      std::memcpy(&bytes[i * stride], &e.bytes[i * e.elementSize], e.elementSize);
    const int view = addBufferView(bytes.data(), bytes.size(), kArrayBuffer);
    if (stride != e.elementSize) doc_["bufferViews"][view]["byteStride"] = stride;
    json accessor = {
        {"bufferView", view}, {"componentType", e.componentType}, {"count", e.count}, {"type", e.type}};
    if (e.normalized) accessor["normalized"] = true;
    if (bounds) std::tie(accessor["min"], accessor["max"]) = elementBounds(e);
    return push("accessors", accessor);
  }

  int addIndexAccessor(const std::vector<uint32_t>& indices) {
    json accessor = {{"bufferView", addBufferView(indices.data(), indices.size() * 4, kElementArrayBuffer)},
                     {"componentType", kUnsignedInt},
                     {"count", indices.size()},
                     {"type", "SCALAR"}};
    return push("accessors", accessor);
  }

  int addPngTexture(const std::vector<uint8_t>& png, const std::string& name) {
    const int view = addBufferView(png.data(), png.size(), 0);
    const int image = push("images", {{"bufferView", view}, {"mimeType", "image/png"}, {"name", name}});
    if (!doc_.contains("samplers")) doc_["samplers"] = json::array();
    const int sampler = push("samplers", {{"magFilter", 9729}, {"minFilter", 9729}});
    return push("textures", {{"source", image}, {"sampler", sampler}, {"name", name}});
  }

  int push(const char* key, json value) {
    if (!doc_.contains(key)) doc_[key] = json::array();
    doc_[key].push_back(std::move(value));
    return static_cast<int>(doc_[key].size()) - 1;
  }

  void useExtension(const std::string& name) {
    if (!doc_.contains("extensionsUsed")) doc_["extensionsUsed"] = json::array();
    json& used = doc_["extensionsUsed"];
    if (std::find(used.begin(), used.end(), name) == used.end()) used.push_back(name);
  }

  // GLB 2.0: header, JSON chunk padded with spaces, BIN chunk padded with zeros (glTF spec, "Binary glTF").
  std::vector<uint8_t> finish() {
    bin_.resize((bin_.size() + 3) / 4 * 4, 0);
    if (bin_.empty()) {
      doc_.erase("buffers");
    } else {
      doc_["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    }
    std::string text = doc_.dump();
    text.resize((text.size() + 3) / 4 * 4, ' ');
    const bool hasBin = !bin_.empty();
    const std::size_t total = 12 + 8 + text.size() + (hasBin ? 8 + bin_.size() : 0);
    std::vector<uint8_t> out;
    out.reserve(total);
    const auto put32 = [&](uint32_t v) {
      for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
    };
    put32(0x46546C67u);  // "glTF"
    put32(2);
    put32(static_cast<uint32_t>(total));
    put32(static_cast<uint32_t>(text.size()));
    put32(0x4E4F534Au);  // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    if (hasBin) {
      put32(static_cast<uint32_t>(bin_.size()));
      put32(0x004E4942u);  // "BIN\0"
      out.insert(out.end(), bin_.begin(), bin_.end());
    }
    return out;
  }

 private:
  json doc_;
  std::vector<uint8_t> bin_;
};

bool isDataUri(const std::string& uri) {
  return uri.rfind("data:", 0) == 0;
}

// Moves every buffer of the source into the builder's single buffer and repoints the source's bufferViews.
// Views the builder added before (a base colour texture) already index its buffer and stay as they are: a
// base colour on a GLB that kept its source pointed into the source's data before.
void mergeBuffers(const GltfSource& source, GlbBuilder& builder) {
  json& doc = builder.doc();
  std::vector<std::size_t> base;
  for (const auto& buffer : source.buffers) base.push_back(builder.append(buffer.data(), buffer.size()));
  const std::size_t sourceViews =
      source.document.contains("bufferViews") ? source.document["bufferViews"].size() : std::size_t{0};
  if (doc.contains("bufferViews")) {
    for (std::size_t v = 0; v < std::min(sourceViews, doc["bufferViews"].size()); ++v) {
      json& view = doc["bufferViews"][v];
      const std::size_t buffer = view.value("buffer", 0);
      view["buffer"] = 0;
      view["byteOffset"] = view.value("byteOffset", std::size_t{0}) + base.at(buffer);
    }
  }
  if (doc.contains("images")) {
    for (std::size_t i = 0; i < doc["images"].size(); ++i) {
      const json& image = doc["images"][i];
      if (image.contains("uri") && !isDataUri(image["uri"].get<std::string>())) {
        throw InputError("image " + std::to_string(i) + " refers to an external file (" +
                         image["uri"].get<std::string>() +
                         "); a GLB must hold it: load the model as .glb or with embedded images");
      }
    }
  }
}

Eigen::Vector3d vectorAt(const std::vector<double>& values, int32_t v) {
  return {values[3 * v], values[3 * v + 1], values[3 * v + 2]};
}

// The material of a primitive that has none: brushed metal along the field, or, under a base-colour texture
// (a synthesized one), a dielectric that shows the texture's own colours.
json fieldMaterial(bool textured) {
  return {{"name", "field"},
          {"pbrMetallicRoughness",
           {{"metallicFactor", textured ? 0.0 : 1.0}, {"roughnessFactor", textured ? 0.6 : 0.35}}}};
}

json& materialOf(json& doc, json& primitive, int& defaultMaterial, bool textured) {
  if (!primitive.contains("material")) {
    if (defaultMaterial < 0) {
      if (!doc.contains("materials")) doc["materials"] = json::array();
      doc["materials"].push_back(fieldMaterial(textured));
      defaultMaterial = static_cast<int>(doc["materials"].size()) - 1;
    }
    primitive["material"] = defaultMaterial;
  }
  return doc["materials"].at(primitive["material"].get<std::size_t>());
}

json anisotropyExtension(const FieldGlbOptions& options, int texture) {
  json extension = {{"anisotropyStrength", options.anisotropyStrength},
                    {"anisotropyRotation", options.anisotropyRotation}};
  if (texture >= 0) extension["anisotropyTexture"] = {{"index", texture}, {"texCoord", 0}};
  return extension;
}

void addFieldMaterial(json& material, const FieldGlbOptions& options, int anisotropyTexture,
                      int baseColorTexture) {
  material["extensions"][kAnisotropy] = anisotropyExtension(options, anisotropyTexture);
  if (baseColorTexture >= 0)
    material["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", baseColorTexture}};
}

bool hasNormalMap(const json& doc, const json& primitive) {
  if (!primitive.contains("material") || !doc.contains("materials")) return false;
  const json& material = doc["materials"].at(primitive["material"].get<std::size_t>());
  return material.contains("normalTexture");
}

// Attributes of one source primitive: world directions taken back to the mesh's own space. vertices: the
// source vertex of each of the primitive's vertices (split ones: gltf_vertex_split.h), or empty: its own.
void addPrimitiveAttributes(const FieldGlbContent& content, const GltfPrimitiveInstance& instance,
                            std::size_t firstSource, const std::vector<uint32_t>& vertices, bool keepTangents,
                            json& primitive, GlbBuilder& builder) {
  Eigen::Matrix3d linear;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) linear(r, c) = instance.transform[4 * c + r];
  const Eigen::Matrix3d toLocal = linear.inverse();
  // Normals transform with the inverse transpose.
  const Eigen::Matrix3d normalToLocal = linear.transpose();
  std::vector<float> tangents, field, normals;
  const std::size_t count = vertices.empty() ? instance.vertexCount : vertices.size();
  for (std::size_t i = 0; i < count; ++i) {
    const int32_t v = content.mesh->sourceToWelded.at(firstSource + (vertices.empty() ? i : vertices[i]));
    const Eigen::Vector3d t = (toLocal * vectorAt(content.vertexTangent, v)).normalized();
    const Eigen::Vector3d u = toLocal * vectorAt(content.vertexField, v);
    for (int d = 0; d < 3; ++d) tangents.push_back(static_cast<float>(t[d]));
    tangents.push_back(1.0f);
    for (int d = 0; d < 3; ++d) field.push_back(static_cast<float>(u[d]));
    const Eigen::Vector3d n = (normalToLocal * vectorAt(content.vertexNormal, v)).normalized();
    for (int d = 0; d < 3; ++d) normals.push_back(static_cast<float>(n[d]));
  }
  json& attributes = primitive["attributes"];
  // Without NORMAL a viewer must shade flat and ignore TANGENT (glTF 2.0, 3.7.2.1), losing the field.
  if (!keepTangents && !attributes.contains("NORMAL")) {
    attributes["NORMAL"] = builder.addFloatAccessor(normals, 3, "VEC3", false);
  }
  if (!keepTangents) attributes["TANGENT"] = builder.addFloatAccessor(tangents, 4, "VEC4", false);
  attributes["_FIELD"] = builder.addFloatAccessor(field, 3, "VEC3", false);
}

// The first TEXCOORD_n a primitive does not have (n >= 1: TEXCOORD_0 is the model's UVs).
int freeTexcoordSet(const json& attributes) {
  int n = 1;
  while (attributes.contains("TEXCOORD_" + std::to_string(n))) ++n;
  return n;
}

// A kept primitive given the stripe phase as a texture coordinate (content.cornerTexcoord1 of faces
// [firstFace, ...)): its vertices split where the phase differs, every attribute and morph target gathered
// for them (but those addPrimitiveAttributes writes), the phase as its first free TEXCOORD_n (named in the
// primitive's extras), and its triangles indexed anew. Returns the new vertices' source vertices.
std::vector<uint32_t> splitForPhase(const FieldGlbContent& content, const GltfPrimitiveInstance& instance,
                                    std::size_t firstFace, bool keepTangents, json& primitive,
                                    GlbBuilder& builder) {
  VertexSplit split =
      splitVertices(instance.vertexCount, instance.corners, &content.cornerTexcoord1[6 * firstFace]);
  const auto gathered = [&](const json& index) {
    if (!index.is_number_integer()) throw InputError("glTF export: an attribute names no accessor");
    const AccessorElements elements =
        readAccessorElements(*content.source, index.get<int>(), instance.vertexCount);
    const json& original = content.source->document["accessors"][index.get<std::size_t>()];
    return builder.addElementsAccessor(gatherElements(elements, split.sourceVertex),
                                       original.contains("min") || original.contains("max"));
  };
  for (auto& [name, index] : primitive["attributes"].items()) {
    if (name == "_FIELD" || (name == "TANGENT" && !keepTangents)) continue;
    index = gathered(index);
  }
  if (primitive.contains("targets"))
    for (json& target : primitive["targets"])
      for (auto& [name, index] : target.items()) index = gathered(index);
  const int set = freeTexcoordSet(primitive["attributes"]);
  primitive["attributes"]["TEXCOORD_" + std::to_string(set)] =
      builder.addFloatAccessor(split.values, 2, "VEC2", false);
  // Named where the primitive's extras can hold it (glTF asks objects of them, but a file may not keep to
  // it).
  const bool named = !primitive.contains("extras") ||
                     (primitive["extras"].is_object() && (!primitive["extras"].contains(kGlbExtrasKey) ||
                                                          primitive["extras"][kGlbExtrasKey].is_object()));
  if (named) primitive["extras"][kGlbExtrasKey]["stripePhaseTexCoord"] = set;
  primitive["indices"] = builder.addIndexAccessor(split.indices);
  primitive["mode"] = 4;  // strips and fans unrolled
  return std::move(split.sourceVertex);
}

json fromSource(const FieldGlbContent& content, const FieldGlbOptions& options, GlbBuilder& builder,
                int baseColorTexture) {
  const GltfSource& source = *content.source;
  json& doc = builder.doc();
  mergeBuffers(source, builder);
  std::size_t total = 0;
  for (const auto& p : source.primitives) total += p.vertexCount;
  if (total != content.mesh->sourceToWelded.size()) {
    throw InputError("the glTF document does not match the loaded mesh (" + std::to_string(total) +
                     " source vertices, the mesh has " + std::to_string(content.mesh->sourceToWelded.size()) +
                     ")");
  }
  int anisotropyTexture = -1;
  if (!content.anisotropyPng.empty())
    anisotropyTexture = builder.addPngTexture(content.anisotropyPng, "anisotropy");
  const bool phase = !content.cornerTexcoord1.empty();
  std::size_t faces = 0;
  for (const auto& p : source.primitives) faces += p.corners.size() / 3;
  if (phase && faces != static_cast<std::size_t>(content.mesh->numFaces()))
    throw InputError("the glTF document does not match the loaded mesh (" + std::to_string(faces) +
                     " triangles, the mesh has " + std::to_string(content.mesh->numFaces()) + ")");
  int defaultMaterial = -1;
  std::map<std::pair<int, int>, bool> written;  // a mesh instanced twice takes its first instance's field
  std::size_t firstSource = 0, firstFace = 0;
  for (const GltfPrimitiveInstance& instance : source.primitives) {
    json& primitive = doc["meshes"][instance.mesh]["primitives"][instance.primitive];
    if (!written[{instance.mesh, instance.primitive}]) {
      written[{instance.mesh, instance.primitive}] = true;
      const bool normalMapped = hasNormalMap(doc, primitive);
      const std::vector<uint32_t> vertices =
          phase ? splitForPhase(content, instance, firstFace, normalMapped, primitive, builder)
                : std::vector<uint32_t>();
      addPrimitiveAttributes(content, instance, firstSource, vertices, normalMapped, primitive, builder);
      json& material = materialOf(doc, primitive, defaultMaterial, baseColorTexture >= 0);
      addFieldMaterial(material, options, normalMapped ? anisotropyTexture : -1, baseColorTexture);
    }
    firstSource += instance.vertexCount;
    firstFace += instance.corners.size() / 3;
  }
  return doc;
}

// A vertex per (welded vertex, UV, TEXCOORD_1) triple, in welded order, so a reload welds back to the same
// numbering.
void fromMesh(const FieldGlbContent& content, const FieldGlbOptions& options, GlbBuilder& builder,
              int baseColorTexture) {
  const SurfaceMesh& mesh = *content.mesh;
  const bool uvs = !content.cornerUVs.empty(), second = !content.cornerTexcoord1.empty();
  using Key = std::array<float, 4>;
  const auto keyOf = [&](int32_t c) {
    Key k{0.0f, 0.0f, 0.0f, 0.0f};
    if (uvs) k[0] = content.cornerUVs[2 * c], k[1] = content.cornerUVs[2 * c + 1];
    if (second) k[2] = content.cornerTexcoord1[2 * c], k[3] = content.cornerTexcoord1[2 * c + 1];
    return k;
  };
  std::vector<std::map<Key, uint32_t>> splits(mesh.numVertices());
  for (int32_t c = 0; c < mesh.numFaces() * 3; ++c) splits[mesh.triangles[c]].emplace(keyOf(c), 0);
  std::vector<float> positions, normals, texcoords, texcoords1, tangents, field;
  uint32_t next = 0;
  for (int32_t v = 0; v < mesh.numVertices(); ++v) {
    if (splits[v].empty())
      splits[v].emplace(Key{0.0f, 0.0f, 0.0f, 0.0f}, 0);  // keep unused vertices numbered
    for (auto& [key, index] : splits[v]) {
      index = next++;
      for (int d = 0; d < 3; ++d) {
        positions.push_back(static_cast<float>(mesh.positions[3 * v + d]));
        normals.push_back(static_cast<float>(content.vertexNormal[3 * v + d]));
        tangents.push_back(static_cast<float>(content.vertexTangent[3 * v + d]));
        field.push_back(static_cast<float>(content.vertexField[3 * v + d]));
      }
      tangents.push_back(1.0f);
      texcoords.insert(texcoords.end(), {key[0], key[1]});
      texcoords1.insert(texcoords1.end(), {key[2], key[3]});
    }
  }
  std::vector<uint32_t> indices;
  for (int32_t c = 0; c < mesh.numFaces() * 3; ++c) indices.push_back(splits[mesh.triangles[c]].at(keyOf(c)));
  json attributes = {{"POSITION", builder.addFloatAccessor(positions, 3, "VEC3", true)},
                     {"NORMAL", builder.addFloatAccessor(normals, 3, "VEC3", false)},
                     {"TANGENT", builder.addFloatAccessor(tangents, 4, "VEC4", false)},
                     {"_FIELD", builder.addFloatAccessor(field, 3, "VEC3", false)}};
  if (uvs) attributes["TEXCOORD_0"] = builder.addFloatAccessor(texcoords, 2, "VEC2", false);
  if (second) attributes["TEXCOORD_1"] = builder.addFloatAccessor(texcoords1, 2, "VEC2", false);
  json material = fieldMaterial(baseColorTexture >= 0);
  addFieldMaterial(material, options, -1, baseColorTexture);
  const int materialIndex = builder.push("materials", material);
  json primitive = {{"attributes", attributes},
                    {"indices", builder.addIndexAccessor(indices)},
                    {"material", materialIndex},
                    {"mode", 4}};
  if (second) primitive["extras"][kGlbExtrasKey]["stripePhaseTexCoord"] = 1;
  const int meshIndex = builder.push("meshes", {{"primitives", json::array({primitive})}});
  const int node = builder.push("nodes", {{"mesh", meshIndex}});
  builder.doc()["scenes"] = json::array({{{"nodes", json::array({node})}}});
  builder.doc()["scene"] = 0;
}

void checkContent(const FieldGlbContent& content) {
  if (!content.mesh) throw InputError("GLB export: no mesh");
  const std::size_t n = 3 * static_cast<std::size_t>(content.mesh->numVertices());
  if (content.vertexField.size() != n || content.vertexTangent.size() != n) {
    throw InputError("GLB export: field and tangents need 3 values per vertex");
  }
  if (content.vertexNormal.size() != n) throw InputError("GLB export: normals missing");
  if (!content.source && !content.cornerUVs.empty() &&
      content.cornerUVs.size() != 6 * static_cast<std::size_t>(content.mesh->numFaces())) {
    throw InputError("GLB export: expected 6 UV values per face");
  }
  if (!content.cornerTexcoord1.empty() &&
      content.cornerTexcoord1.size() != 6 * static_cast<std::size_t>(content.mesh->numFaces()))
    throw InputError("GLB export: expected 6 TEXCOORD_1 values per face");
}

}  // namespace

bool sourceHasNormalMappedMaterial(const GltfSource& source) {
  for (const GltfPrimitiveInstance& instance : source.primitives) {
    if (hasNormalMap(source.document,
                     source.document["meshes"][instance.mesh]["primitives"][instance.primitive]))
      return true;
  }
  return false;
}

std::vector<uint8_t> writeFieldGlb(const FieldGlbContent& content, const FieldGlbOptions& options) {
  checkContent(content);
  GlbBuilder builder(content.source ? content.source->document : json{{"asset", {{"version", "2.0"}}}});
  json& doc = builder.doc();
  doc["asset"]["generator"] = "tangent-field-designer";
  const int baseColorTexture =
      options.baseColorPng.empty() ? -1 : builder.addPngTexture(options.baseColorPng, "texture");
  if (content.source) {
    fromSource(content, options, builder, baseColorTexture);
  } else {
    fromMesh(content, options, builder, baseColorTexture);
  }
  builder.useExtension(kAnisotropy);
  json extras = json::object();
  if (!options.flowMapPng.empty())
    extras["flowMapTexture"] = builder.addPngTexture(options.flowMapPng, "flow map");
  if (!options.design.is_null()) extras["design"] = options.design;
  if (!extras.empty()) doc["extras"][kGlbExtrasKey] = extras;
  return builder.finish();
}

nlohmann::json readEmbeddedDesign(const uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  if (size >= 20 && std::memcmp(data, "glTF", 4) == 0) {
    const uint32_t length =
        uint32_t{data[12]} | uint32_t{data[13]} << 8 | uint32_t{data[14]} << 16 | uint32_t{data[15]} << 24;
    if (length > size - 20) throw InputError("truncated GLB: JSON chunk extends past the end");
    text = text.substr(20, length);
  }
  const json doc = json::parse(text.begin(), text.end(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) throw InputError("not a glTF document (invalid JSON)");
  const auto extras = doc.find("extras");
  if (extras == doc.end() || !extras->is_object() || !extras->contains(kGlbExtrasKey)) return nullptr;
  const json& ours = (*extras)[kGlbExtrasKey];
  return ours.is_object() && ours.contains("design") ? ours["design"] : json();
}

}  // namespace tvf
