#include "mesh/mesh_hash.h"

#include <cstring>

namespace tvf {

uint64_t meshHash(const SurfaceMesh& mesh) {
  uint64_t h = 0xcbf29ce484222325ull;
  const auto word = [&h](uint32_t w) {
    h ^= w;
    h *= 0x100000001b3ull;
  };
  for (const double x : mesh.positions) {
    const float f = static_cast<float>(x);
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    word(bits);
  }
  for (const int32_t v : mesh.triangles) word(static_cast<uint32_t>(v));
  return h;
}

}  // namespace tvf
