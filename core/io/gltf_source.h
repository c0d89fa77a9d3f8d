#pragma once
// A glTF document kept for re-export: its JSON as written, its buffers resolved, and the triangle primitives
// in the order the loader welds them (so mesh.sourceToWelded can be split back per primitive).
#include <array>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tvf {

struct GltfPrimitiveInstance {
  int mesh = 0, primitive = 0;
  uint32_t vertexCount = 0;            // the POSITION accessor's count
  std::array<double, 16> transform{};  // node world transform, column-major
  // The primitive's triangles as the loader takes them (strips and fans unrolled), 3 of its own vertex
  // indices each: the welded mesh's faces are every instance's in turn.
  std::vector<uint32_t> corners;
};

struct GltfSource {
  nlohmann::json document;
  std::vector<std::vector<uint8_t>> buffers;      // buffer i's bytes
  std::vector<GltfPrimitiveInstance> primitives;  // triangle primitives in load (welding) order
};

// Same checks and messages as loadMeshFromMemory for glTF/GLB; baseDir resolves external buffers.
GltfSource loadGltfSource(const uint8_t* data, std::size_t size, bool binary, const std::string& baseDir = "",
                          const std::string& name = "glTF data");

}  // namespace tvf
