#pragma once
// A triangle soup as it comes from a file, before any topology is built.
#include <cstdint>
#include <string>
#include <vector>

// Every reader and check of a mesh reports through InputError, so its users get it with the mesh.
#include "common/input_error.h"

namespace tvf {

struct SurfaceMesh {
  std::vector<double> positions;   // x, y, z per vertex
  std::vector<int32_t> triangles;  // i, j, k per face, in the file's winding
  // u, v per face corner (6 floats per face) when the source carries texture coordinates; else empty.
  std::vector<float> cornerUVs;
  // For glTF: the welded vertex of every source vertex (all primitives concatenated in load order); else
  // empty.
  std::vector<int32_t> sourceToWelded;

  int32_t numVertices() const { return static_cast<int32_t>(positions.size() / 3); }
  int32_t numFaces() const { return static_cast<int32_t>(triangles.size() / 3); }
  bool hasUVs() const { return !cornerUVs.empty(); }
  // The corner (0, 1, 2) of face f at vertex v, or -1 when f does not use v.
  int cornerOf(int32_t f, int32_t v) const {
    for (int c = 0; c < 3; ++c)
      if (triangles[3 * f + c] == v) return c;
    return -1;
  }
};

}  // namespace tvf
