#include "direction/combing.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "common/angles.h"
#include "direction/representative_directions.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

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

namespace {

// Of d's N turns about n (d in the plane of n), the one nearest `reference` (in the plane), and how near:
// the cosine of the angle between them. Without trigonometry for N = 2 and 4 (a line or cross field: the
// stripes' families, combed every edit).
std::pair<Eigen::Vector3d, double> nearestTurn(const Eigen::Vector3d& d, const Eigen::Vector3d& reference,
                                               const Eigen::Vector3d& n, int symmetry) {
  const double length = reference.norm();
  if (!(length > 0)) return {d, 1.0};
  const Eigen::Vector3d r = reference / length;
  if (symmetry == 2 || symmetry == 4) {
    const Eigen::Vector3d q = n.cross(d);
    const double along = d.dot(r), across = symmetry == 4 ? q.dot(r) : 0.0;
    if (std::abs(along) >= std::abs(across)) return {along < 0 ? Eigen::Vector3d(-d) : d, std::abs(along)};
    return {across < 0 ? Eigen::Vector3d(-q) : q, std::abs(across)};
  }
  const Eigen::Vector3d turned = closestRotation(d, r, n, symmetry);
  return {turned, turned.dot(r)};
}

}  // namespace

std::vector<double> combVertexDirections(const MeshTopology& t, const std::vector<double>& normals,
                                         const std::vector<double>& vertexDirections, int symmetry) {
  std::vector<double> out = vertexDirections;
  if (symmetry < 2) return out;
  auto normal = [&](int32_t v) { return Eigen::Vector3d(&normals[3 * v]); };
  // Each vertex's own direction in its tangent plane, unit (zero where the field is).
  std::vector<Eigen::Vector3d> own(t.numVertices);
  for (int32_t v = 0; v < t.numVertices; ++v) {
    const Eigen::Vector3d d(&vertexDirections[3 * v]), n = normal(v);
    const Eigen::Vector3d inPlane = d - n * n.dot(d);
    const double length = inPlane.norm();
    own[v] =
        length > 0 && std::isfinite(length) ? Eigen::Vector3d(inPlane / length) : Eigen::Vector3d::Zero();
  }
  std::vector<Eigen::Vector3d> combed = own;
  const auto towards = [&](int32_t from, int32_t v) {
    const Eigen::Vector3d n = normal(v);
    return nearestTurn(own[v], combed[from] - n * n.dot(combed[from]), n, symmetry);
  };
  // Prim's tree by a bucket queue (the misalignment 1 - cos in kBuckets steps): the same tree up to ties
  // within a step, at a fraction of a binary heap's cost (bunny00: 21 -> 12-14 ms natively).
  constexpr int kBuckets = 4096;
  const double perBucket = kBuckets / (1.0 - std::cos(M_PI / symmetry) + 1e-9);
  struct Item {
    int32_t vertex, parent;
  };
  // Each bucket first in, first out: within a step the tree grows breadth-first, its paths short (last in,
  // first out, they wind round the singularities and the disagreeing edges tripled on bunny00).
  std::vector<std::vector<Item>> buckets(kBuckets);
  std::vector<size_t> head(kBuckets, 0);
  std::vector<uint8_t> done(t.numVertices, 0);
  for (int32_t root = 0; root < t.numVertices; ++root) {
    if (done[root]) continue;
    buckets[0].push_back({root, -1});
    for (int lowest = 0; lowest < kBuckets;) {
      if (head[lowest] == buckets[lowest].size()) {
        buckets[lowest].clear(), head[lowest] = 0;
        ++lowest;
        continue;
      }
      const Item item = buckets[lowest][head[lowest]++];
      const int32_t v = item.vertex;
      if (done[v]) continue;
      done[v] = 1;
      if (own[v].squaredNorm() == 0) continue;  // no direction to take or pass on
      if (item.parent >= 0) combed[v] = towards(item.parent, v).first;
      for (int32_t k = t.vertexEdgeStart[v]; k < t.vertexEdgeStart[v + 1]; ++k) {
        const int32_t e = t.vertexEdgeList[k];
        const int32_t w = t.edgeVertices[2 * e] == v ? t.edgeVertices[2 * e + 1] : t.edgeVertices[2 * e];
        if (done[w] || own[w].squaredNorm() == 0) continue;
        const int b = std::clamp(static_cast<int>((1.0 - towards(v, w).second) * perBucket), 0, kBuckets - 1);
        buckets[b].push_back({w, v});
        lowest = std::min(lowest, b);
      }
    }
  }
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (own[v].squaredNorm() == 0) continue;
    const double length = Eigen::Vector3d(&vertexDirections[3 * v]).norm();
    for (int k = 0; k < 3; ++k) out[3 * v + k] = combed[v][k] * length;
  }
  return out;
}

int32_t disagreeingEdges(const MeshTopology& t, const std::vector<double>& normals,
                         const std::vector<double>& dirs, int symmetry) {
  int32_t count = 0;
  for (int32_t e = 0; e < t.numEdges; ++e) {
    if (t.edgeFaces[2 * e] < 0 || t.edgeFaces[2 * e + 1] < 0) continue;
    const int32_t a = t.edgeVertices[2 * e], b = t.edgeVertices[2 * e + 1];
    const Eigen::Vector3d n(&normals[3 * b]), da(&dirs[3 * a]), db(&dirs[3 * b]);
    if (da.squaredNorm() == 0 || db.squaredNorm() == 0) continue;
    count += std::abs(symmetricAngle(da - n * n.dot(da), db, n, 1)) > M_PI / symmetry;
  }
  return count;
}

Eigen::Vector3d combedDirection(const CombedDirections& combed, int32_t f, const double bary[3]) {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) u += bary[c] * Eigen::Vector3d(&combed.corner[9 * f + 3 * c]);
  const double length = u.norm();
  return length > 0 ? Eigen::Vector3d(u / length) : Eigen::Vector3d(&combed.face[3 * f]);
}

}  // namespace tvf
