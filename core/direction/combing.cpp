#include "direction/combing.h"

#include <cmath>
#include <queue>

#include "direction/representative_directions.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

constexpr double kTwoPi = 6.283185307179586;

Eigen::Vector3d rotated(const Eigen::Vector3d& v, const Eigen::Vector3d& normal, double angle) {
  return std::cos(angle) * v + std::sin(angle) * normal.cross(v);
}

// Of v's N rotations about `normal` (after projecting v into the plane), the one closest to `reference`.
Eigen::Vector3d closestRotation(const Eigen::Vector3d& v, const Eigen::Vector3d& reference,
                                const Eigen::Vector3d& normal, int symmetry) {
  const Eigen::Vector3d inPlane = (v - normal * normal.dot(v)).normalized();
  if (!inPlane.allFinite()) return reference;
  const double toReference = std::atan2(inPlane.cross(reference).dot(normal), inPlane.dot(reference));
  const double step = kTwoPi / symmetry;
  return rotated(inPlane, normal, step * std::round(toReference / step));
}

// Faces f and g across edge e lie in one chart when both shared corners keep their UVs.
bool sameChart(const SurfaceMesh& mesh, const MeshTopology& t, const std::vector<float>& uvs, int32_t e,
               int32_t f, int32_t g) {
  if (uvs.empty()) return true;
  for (int k = 0; k < 2; ++k) {
    const int32_t v = t.edgeVertices[2 * e + k];
    const int cf = mesh.cornerOf(f, v), cg = mesh.cornerOf(g, v);
    if (uvs[6 * f + 2 * cf] != uvs[6 * g + 2 * cg] || uvs[6 * f + 2 * cf + 1] != uvs[6 * g + 2 * cg + 1])
      return false;
  }
  return true;
}

}  // namespace

CombedDirections combDirections(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                                const std::vector<double>& faceDirections, int symmetry,
                                const std::vector<float>& cornerUVs) {
  CombedDirections out;
  out.face = faceDirections;
  auto normal = [&](int32_t f) { return Eigen::Vector3d(&g.faceNormal[3 * f]); };
  auto direction = [&](int32_t f) { return Eigen::Map<Eigen::Vector3d>(&out.face[3 * f]); };
  // Misalignment of g's representative with f's combed direction (projected into g's plane).
  auto cost = [&](int32_t f, int32_t h) {
    const Eigen::Vector3d from = direction(f);
    const Eigen::Vector3d to(&faceDirections[3 * h]);
    return std::abs(symmetricAngle(from - normal(h) * normal(h).dot(from), to, normal(h), symmetry));
  };
  std::vector<uint8_t> done(t.numFaces, 0);
  using Item = std::pair<double, std::pair<int32_t, int32_t>>;  // cost, (face, parent)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int32_t root = 0; root < t.numFaces; ++root) {
    if (done[root]) continue;
    queue.push({0.0, {root, -1}});
    while (!queue.empty()) {
      const auto [c, item] = queue.top();
      const auto [f, parent] = item;
      queue.pop();
      if (done[f]) continue;
      done[f] = 1;
      if (parent >= 0) {
        const Eigen::Vector3d reference = direction(parent);
        direction(f) = closestRotation(Eigen::Vector3d(&faceDirections[3 * f]),
                                       reference - normal(f) * normal(f).dot(reference), normal(f), symmetry);
      }
      for (int k = 0; k < 3; ++k) {
        const int32_t e = t.edgeOf(f, k), h = t.otherFace(e, f);
        if (h >= 0 && !done[h] && sameChart(mesh, t, cornerUVs, e, f, h)) queue.push({cost(f, h), {h, f}});
      }
    }
  }
  for (int32_t e = 0; e < t.numEdges; ++e) {
    const int32_t f = t.edgeFaces[2 * e], h = t.edgeFaces[2 * e + 1];
    if (f >= 0 && h >= 0 && sameChart(mesh, t, cornerUVs, e, f, h)) {
      const Eigen::Vector3d a = direction(f);
      out.flippedEdges += (a - normal(h) * normal(h).dot(a)).normalized().dot(direction(h)) < 0;
    }
  }
  const std::vector<double> vertex = vertexRepresentatives(mesh, t, g, faceDirections, symmetry);
  out.corner.resize(9 * t.numFaces);
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d v(&vertex[3 * mesh.triangles[3 * f + c]]);
      const Eigen::Vector3d r = v.squaredNorm() > 0 ? closestRotation(v, direction(f), normal(f), symmetry)
                                                    : Eigen::Vector3d(direction(f));
      for (int k = 0; k < 3; ++k) out.corner[9 * f + 3 * c + k] = r[k];
    }
  return out;
}

Eigen::Vector3d combedDirection(const CombedDirections& combed, int32_t f, const double bary[3]) {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) u += bary[c] * Eigen::Vector3d(&combed.corner[9 * f + 3 * c]);
  const double length = u.norm();
  return length > 0 ? Eigen::Vector3d(u / length) : Eigen::Vector3d(&combed.face[3 * f]);
}

}  // namespace tvf
