#pragma once
// A kept glTF primitive given a per-corner attribute its vertices cannot hold (a stripe pattern's phase as a
// texture coordinate, docs/export.md): its vertices split where that attribute differs between the faces
// round them, and every attribute and morph target gathered for the new vertices. The new vertices follow
// the source's vertex order (a vertex's copies in a row), so the file welds back to the same numbering.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/gltf_source.h"

namespace tvf {

// An accessor's elements tightly packed (its bufferView's stride removed, sparse values substituted, zeros
// where it has no bufferView), and what describes them.
struct AccessorElements {
  int componentType = 0;
  std::string type;  // "SCALAR", "VEC2", "VEC3" or "VEC4"
  bool normalized = false;
  std::size_t components = 0, elementSize = 0, count = 0;
  std::vector<uint8_t> bytes;
};

// Throws InputError naming the accessor when it is out of range, of a matrix type or unknown component type,
// has other than expectedCount elements (its primitive's vertex count), or reaches past its buffer.
AccessorElements readAccessorElements(const GltfSource& source, int accessor, std::size_t expectedCount);

struct VertexSplit {
  std::vector<uint32_t> sourceVertex;  // per new vertex: the source vertex it copies
  std::vector<float> values;           // 2 per new vertex: the per-corner attribute's value there
  std::vector<uint32_t> indices;       // per corner: its new vertex
};

// corners: the primitive's triangles (GltfPrimitiveInstance::corners); cornerValues: 2 per corner. A vertex
// per (source vertex, value) pair; a source vertex no triangle uses keeps one (values 0).
VertexSplit splitVertices(uint32_t vertexCount, const std::vector<uint32_t>& corners,
                          const float* cornerValues);

// The elements of `from` at the split's source vertices.
AccessorElements gatherElements(const AccessorElements& from, const std::vector<uint32_t>& sourceVertex);

// Per component: the smallest and largest value over the elements, as an accessor's min and max.
std::pair<nlohmann::json, nlohmann::json> elementBounds(const AccessorElements& elements);

}  // namespace tvf
