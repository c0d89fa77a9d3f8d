#pragma once
// A polygon mesh on a triangle mesh's surface: what the quad remesher makes (nearly all quads).
#include <cstdint>
#include <vector>

namespace tvf {

struct QuadMesh {
  std::vector<double> positions;      // 3 per vertex, on the input surface
  std::vector<int32_t> faceStart;     // faces + 1: face k is faceVertices[faceStart[k], faceStart[k + 1])
  std::vector<int32_t> faceVertices;  // counter-clockwise seen from the surface's outside
  std::vector<int32_t> vertexFace;    // per vertex, the input face it lies in
  int32_t numFaces() const { return faceStart.empty() ? 0 : static_cast<int32_t>(faceStart.size()) - 1; }
  int32_t numVertices() const { return static_cast<int32_t>(positions.size() / 3); }
};

}  // namespace tvf
