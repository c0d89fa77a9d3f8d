// SPDX-License-Identifier: GPL-2.0-or-later
#include "io/gltf_vertex_split.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include "common/input_error.h"
#include "io/loaders.h"

namespace tvf {
namespace {

using io_detail::componentSize;
using io_detail::fits;
using nlohmann::json;

std::size_t componentCount(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  return 0;  // matrices are never vertex attributes
}

[[noreturn]] void fail(const std::string& what) {
  throw InputError("glTF export: " + what);
}

uint64_t unsignedField(const json& object, const char* key, uint64_t fallback, const std::string& label) {
  if (!object.contains(key)) return fallback;
  const json& value = object[key];
  if (!value.is_number_integer() || value.get<int64_t>() < 0) fail(label + " has an invalid " + key);
  return value.get<uint64_t>();
}

// The bytes of a bufferView: [begin, begin + length) of its buffer, and its stride (0: packed).
struct ViewBytes {
  const uint8_t* data = nullptr;
  uint64_t length = 0, stride = 0;
};

ViewBytes viewBytes(const GltfSource& source, const json& index, const std::string& label) {
  const json& views =
      source.document.contains("bufferViews") ? source.document["bufferViews"] : json::array();
  if (!index.is_number_integer() || index.get<int64_t>() < 0 || index.get<uint64_t>() >= views.size())
    fail(label + " names a bufferView that does not exist");
  const json& view = views[index.get<std::size_t>()];
  const uint64_t buffer = unsignedField(view, "buffer", std::numeric_limits<uint64_t>::max(), label);
  if (buffer >= source.buffers.size()) fail(label + "'s bufferView names a buffer that does not exist");
  const uint64_t offset = unsignedField(view, "byteOffset", 0, label);
  const uint64_t length = unsignedField(view, "byteLength", 0, label);
  const std::vector<uint8_t>& bytes = source.buffers[buffer];
  if (offset > bytes.size() || length > bytes.size() - offset)
    fail(label + "'s bufferView reaches past its buffer");
  return {bytes.data() + offset, length, unsignedField(view, "byteStride", 0, label)};
}

void substituteSparse(const GltfSource& source, const json& sparse, const std::string& label,
                      AccessorElements& out) {
  const uint64_t count = unsignedField(sparse, "count", 0, label + " sparse");
  if (count > out.count || !sparse.contains("indices") || !sparse.contains("values"))
    fail(label + " has an invalid sparse part");
  const json& indices = sparse["indices"];
  const json& values = sparse["values"];
  const std::size_t indexSize =
      componentSize(static_cast<int>(unsignedField(indices, "componentType", 0, label)));
  if (indexSize != 1 && indexSize != 2 && indexSize != 4) fail(label + " has an invalid sparse index type");
  const ViewBytes at = viewBytes(source, indices.value("bufferView", json()), label + " sparse indices");
  const ViewBytes by = viewBytes(source, values.value("bufferView", json()), label + " sparse values");
  const uint64_t atOffset = unsignedField(indices, "byteOffset", 0, label);
  const uint64_t byOffset = unsignedField(values, "byteOffset", 0, label);
  if (!fits(atOffset, count, indexSize, indexSize, at.length) ||
      !fits(byOffset, count, out.elementSize, out.elementSize, by.length))
    fail(label + "'s sparse part reaches past its bufferView");
  for (uint64_t i = 0; i < count; ++i) {
    uint32_t target = 0;
    const uint8_t* p = at.data + atOffset + i * indexSize;
    for (std::size_t k = 0; k < indexSize; ++k) target |= static_cast<uint32_t>(p[k]) << (8 * k);
    if (target >= out.count) fail(label + " has a sparse index out of range");
    std::memcpy(&out.bytes[target * out.elementSize], by.data + byOffset + i * out.elementSize,
                out.elementSize);
  }
}

}  // namespace

AccessorElements readAccessorElements(const GltfSource& source, int index, std::size_t expectedCount) {
  const std::string label = "accessor " + std::to_string(index);
  const json& accessors =
      source.document.contains("accessors") ? source.document["accessors"] : json::array();
  if (index < 0 || static_cast<std::size_t>(index) >= accessors.size()) fail(label + " does not exist");
  const json& accessor = accessors[index];
  AccessorElements out;
  out.componentType = static_cast<int>(unsignedField(accessor, "componentType", 0, label));
  out.type = accessor.value("type", std::string());
  out.normalized = accessor.value("normalized", false);
  out.components = componentCount(out.type);
  const std::size_t size = componentSize(out.componentType);
  if (out.components == 0 || size == 0) fail(label + " is not a vertex attribute's type (" + out.type + ")");
  out.elementSize = out.components * size;
  out.count = unsignedField(accessor, "count", 0, label);
  if (out.count != expectedCount)
    fail(label + " has " + std::to_string(out.count) + " elements where its primitive has " +
         std::to_string(expectedCount) + " vertices");
  out.bytes.assign(out.count * out.elementSize, 0);
  if (accessor.contains("bufferView")) {
    const ViewBytes view = viewBytes(source, accessor["bufferView"], label);
    const uint64_t offset = unsignedField(accessor, "byteOffset", 0, label);
    const uint64_t stride = view.stride ? view.stride : out.elementSize;
    if (!fits(offset, out.count, stride, out.elementSize, view.length))
      fail(label + " reaches past its bufferView");
    for (std::size_t i = 0; i < out.count; ++i)
      std::memcpy(&out.bytes[i * out.elementSize], view.data + offset + i * stride, out.elementSize);
  }
  if (accessor.contains("sparse")) substituteSparse(source, accessor["sparse"], label, out);
  return out;
}

VertexSplit splitVertices(uint32_t vertexCount, const std::vector<uint32_t>& corners,
                          const float* cornerValues) {
  using Key = std::array<float, 2>;
  const auto keyOf = [cornerValues](std::size_t c) {
    Key k{cornerValues[2 * c], cornerValues[2 * c + 1]};
    for (float& x : k)
      if (!std::isfinite(x)) x = 0.0f;  // a NaN would break the map's ordering
    return k;
  };
  std::vector<std::map<Key, uint32_t>> splits(vertexCount);
  for (std::size_t c = 0; c < corners.size(); ++c) splits.at(corners[c]).emplace(keyOf(c), 0);
  VertexSplit out;
  uint32_t next = 0;
  for (uint32_t s = 0; s < vertexCount; ++s) {
    if (splits[s].empty()) splits[s].emplace(Key{0.0f, 0.0f}, 0);
    for (auto& [key, index] : splits[s]) {
      index = next++;
      out.sourceVertex.push_back(s);
      out.values.insert(out.values.end(), key.begin(), key.end());
    }
  }
  out.indices.reserve(corners.size());
  for (std::size_t c = 0; c < corners.size(); ++c) out.indices.push_back(splits[corners[c]].at(keyOf(c)));
  return out;
}

AccessorElements gatherElements(const AccessorElements& from, const std::vector<uint32_t>& sourceVertex) {
  AccessorElements out = from;
  out.count = sourceVertex.size();
  out.bytes.assign(out.count * out.elementSize, 0);
  for (std::size_t i = 0; i < out.count; ++i) {
    if (sourceVertex[i] >= from.count) fail("an attribute has fewer elements than POSITION");
    std::memcpy(&out.bytes[i * out.elementSize], &from.bytes[sourceVertex[i] * from.elementSize],
                out.elementSize);
  }
  return out;
}

std::pair<json, json> elementBounds(const AccessorElements& e) {
  const std::size_t size = e.elementSize / std::max<std::size_t>(e.components, 1);
  std::vector<double> lo(e.components, std::numeric_limits<double>::infinity()), hi(e.components, -lo[0]);
  for (std::size_t i = 0; i < e.count; ++i)
    for (std::size_t k = 0; k < e.components; ++k) {
      const double v =
          io_detail::readComponent(&e.bytes[i * e.elementSize + k * size], e.componentType, false);
      lo[k] = std::min(lo[k], v), hi[k] = std::max(hi[k], v);
    }
  json min = json::array(), max = json::array();
  for (std::size_t k = 0; k < e.components; ++k) {
    if (e.count == 0) lo[k] = hi[k] = 0;
    if (e.componentType == 5126) {
      min.push_back(static_cast<float>(lo[k])), max.push_back(static_cast<float>(hi[k]));
    } else {
      min.push_back(static_cast<int64_t>(lo[k])), max.push_back(static_cast<int64_t>(hi[k]));
    }
  }
  return {min, max};
}

}  // namespace tvf
