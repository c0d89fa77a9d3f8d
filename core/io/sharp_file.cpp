#include "io/sharp_file.h"

#include <Eigen/Geometry>  // cross
#include <algorithm>
#include <array>

namespace tvf {
namespace {

Eigen::Vector3d point(const std::vector<double>& positions, int32_t v) {
  return {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]};
}

Eigen::Vector3d normal(const MeshGeometry& geometry, int32_t f) {
  return {geometry.faceNormal[3 * f], geometry.faceNormal[3 * f + 1], geometry.faceNormal[3 * f + 2]};
}

int32_t cornerOf(const MeshTopology& topology, int32_t face, int32_t edge) {
  for (int32_t c = 0; c < 3; ++c)
    if (topology.edgeOf(face, c) == edge) return c;
  return -1;
}

// The side's direction from corner c to c + 1 of f: the edge's canonical direction times the face's sign.
bool convex(const MeshTopology& topology, const MeshGeometry& geometry, const std::vector<double>& positions,
            int32_t edge) {
  const int32_t f0 = topology.edgeFaces[2 * edge], f1 = topology.edgeFaces[2 * edge + 1];
  if (f0 < 0 || f1 < 0) return true;
  const Eigen::Vector3d along = (point(positions, topology.edgeVertices[2 * edge + 1]) -
                                 point(positions, topology.edgeVertices[2 * edge])) *
                                topology.signOf(f0, cornerOf(topology, f0, edge));
  return normal(geometry, f0).cross(normal(geometry, f1)).dot(along) >= 0;
}

}  // namespace

std::string writeSharpFile(const MeshTopology& topology, const MeshGeometry& geometry,
                           const std::vector<double>& positions, const std::vector<int32_t>& featureEdges) {
  std::vector<int32_t> edges = featureEdges;
  for (int32_t e = 0; e < topology.numEdges; ++e)
    if (topology.isBoundaryEdge[e]) edges.push_back(e);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::array<int32_t, 3>> sides;  // face, corner, type
  for (const int32_t e : edges) {
    const int type = convex(topology, geometry, positions, e) ? 1 : 0;
    for (int k = 0; k < 2; ++k) {
      const int32_t f = topology.edgeFaces[2 * e + k];
      if (f >= 0) sides.push_back({f, cornerOf(topology, f, e), type});
    }
  }
  std::sort(sides.begin(), sides.end());
  std::string out = std::to_string(sides.size()) + "\n";
  for (const auto& s : sides)
    out += std::to_string(s[2]) + "," + std::to_string(s[0]) + "," + std::to_string(s[1]) + "\n";
  return out;
}

}  // namespace tvf
