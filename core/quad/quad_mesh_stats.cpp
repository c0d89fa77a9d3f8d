#include "quad/quad_mesh_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "direction/representative_directions.h"
#include "mesh/closest_point.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

constexpr double kDegrees = 57.29577951308232;

Eigen::Vector3d point(const std::vector<double>& x, int32_t v) {
  return {x[3 * v], x[3 * v + 1], x[3 * v + 2]};
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  const std::size_t k = std::min(values.size() - 1, static_cast<std::size_t>(q * (values.size() - 1) + 0.5));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

// The polygons fanned into triangles (for distances to the quad mesh).
std::vector<int32_t> fanTriangles(const QuadMesh& q) {
  std::vector<int32_t> tris;
  for (int32_t f = 0; f < q.numFaces(); ++f)
    for (int32_t k = q.faceStart[f] + 1; k + 1 < q.faceStart[f + 1]; ++k)
      tris.insert(tris.end(), {q.faceVertices[q.faceStart[f]], q.faceVertices[k], q.faceVertices[k + 1]});
  return tris;
}

// Singularities with another within h: swept in order of x, each compared with those less than h further
// along.
int32_t crowdedSingularities(const SurfaceMesh& surface, const std::vector<Singularity>& singularities,
                             double h) {
  std::vector<Eigen::Vector3d> x;
  for (const Singularity& s : singularities) x.push_back(point(surface.positions, s.vertex));
  std::sort(x.begin(), x.end(),
            [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.x() < b.x(); });
  std::vector<uint8_t> crowded(x.size(), 0);
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size() && x[j].x() - x[i].x() < h; ++j)
      if ((x[j] - x[i]).norm() < h) crowded[i] = crowded[j] = 1;
  return static_cast<int32_t>(std::count(crowded.begin(), crowded.end(), 1));
}

double hausdorff(const QuadMesh& q, const SurfaceMesh& surface) {
  const std::vector<int32_t> tris = fanTriangles(q);
  double worst = 0;
  const TriangleGrid toInput(surface.positions, surface.triangles), toQuads(q.positions, tris);
  for (std::size_t t = 0; t < tris.size(); t += 3) {
    const Eigen::Vector3d a = point(q.positions, tris[t]), b = point(q.positions, tris[t + 1]),
                          c = point(q.positions, tris[t + 2]);
    for (int i = 0; i <= 2; ++i)
      for (int j = 0; i + j <= 2; ++j)
        worst = std::max(worst, toInput.distance(a + (b - a) * (i / 2.0) + (c - a) * (j / 2.0), worst));
  }
  const int32_t nf = static_cast<int32_t>(surface.triangles.size() / 3);
  for (int32_t f = 0; f < nf; ++f) {
    Eigen::Vector3d p[3];
    facePositions(surface, f, p);
    worst = std::max(worst, toQuads.distance(p[0], worst));
    worst = std::max(worst, toQuads.distance((p[0] + p[1] + p[2]) / 3, worst));
  }
  return worst;
}

}  // namespace

QuadMeshStats measureQuadMesh(const QuadMesh& q, const SurfaceMesh& surface, const MeshGeometry& geometry,
                              const std::vector<double>& faceDirections, int symmetry,
                              const std::vector<Singularity>& singularities, double h) {
  QuadMeshStats s;
  s.faces = q.numFaces();
  s.vertices = q.numVertices();
  std::map<std::pair<int32_t, int32_t>, int32_t> directed;
  for (int32_t f = 0; f < s.faces; ++f) {
    const int32_t a = q.faceStart[f], n = q.faceStart[f + 1] - a;
    if (n == 4) ++s.quads;
    for (int32_t k = 0; k < n; ++k) ++directed[{q.faceVertices[a + k], q.faceVertices[a + (k + 1) % n]}];
  }
  s.quadShare = s.faces ? static_cast<double>(s.quads) / s.faces : 0;
  std::map<std::pair<int32_t, int32_t>, int32_t> undirected;
  for (const auto& [e, count] : directed) {
    if (count > 1) s.oriented = false;
    undirected[{std::min(e.first, e.second), std::max(e.first, e.second)}] += count;
  }
  s.edges = static_cast<int32_t>(undirected.size());
  std::vector<int32_t> valence(s.vertices, 0);
  std::vector<uint8_t> onBoundary(s.vertices, 0);
  std::vector<double> angles;
  for (const auto& [e, count] : undirected) {
    ++valence[e.first], ++valence[e.second];
    if (count > 2) s.manifold = false;
    if (count == 1) ++s.boundaryEdges, onBoundary[e.first] = onBoundary[e.second] = 1;
    const Eigen::Vector3d chord = point(q.positions, e.second) - point(q.positions, e.first);
    double angle = 0;
    for (int32_t end : {e.first, e.second}) {
      const int32_t f = q.vertexFace[end];
      const Eigen::Vector3d n(&geometry.faceNormal[3 * f]);
      angle += std::abs(
          symmetricAngle(chord - n * n.dot(chord), Eigen::Vector3d(&faceDirections[3 * f]), n, symmetry));
    }
    angles.push_back(0.5 * angle * kDegrees);
  }
  s.edgeAngleMedianDeg = percentile(angles, 0.5);
  s.edgeAngleP90Deg = percentile(angles, 0.9);
  s.eulerCharacteristic = s.vertices - s.edges + s.faces;

  s.fieldSingularities = static_cast<int32_t>(singularities.size());
  s.crowdedSingularities = crowdedSingularities(surface, singularities, h);
  int32_t near = 0;
  for (int32_t v = 0; v < s.vertices; ++v) {
    if (onBoundary[v] || valence[v] == 4 || valence[v] == 0) continue;
    s.irregular.push_back(v);
    if (valence[v] == 3) ++s.valence3;
    if (valence[v] == 5) ++s.valence5;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Singularity& sing : singularities)
      nearest = std::min(nearest, (point(q.positions, v) - point(surface.positions, sing.vertex)).norm() / h);
    if (nearest <= 2) ++near;
    s.irregularFarthest = std::max(s.irregularFarthest, std::isfinite(nearest) ? nearest : 1e300);
  }
  s.irregularVertices = static_cast<int32_t>(s.irregular.size());
  s.irregularNearSingularity = s.irregularVertices ? static_cast<double>(near) / s.irregularVertices : 1;

  std::vector<double> aspects;
  for (int32_t f = 0; f < s.faces; ++f) {
    const int32_t a = q.faceStart[f], n = q.faceStart[f + 1] - a;
    Eigen::Vector3d newell = Eigen::Vector3d::Zero(), normals = Eigen::Vector3d::Zero();
    double len[4] = {0, 0, 0, 0}, shortest = 1e300;
    bool repeated = false;
    for (int32_t k = 0; k < n; ++k) {
      const int32_t v = q.faceVertices[a + k], w = q.faceVertices[a + (k + 1) % n];
      for (int32_t j = k + 1; j < n; ++j) repeated |= q.faceVertices[a + j] == v;
      const Eigen::Vector3d x = point(q.positions, v), y = point(q.positions, w);
      newell += x.cross(y);
      normals += Eigen::Vector3d(&geometry.faceNormal[3 * q.vertexFace[v]]);
      const double l = (y - x).norm();
      if (k < 4) len[k] = l;
      shortest = std::min(shortest, l);
    }
    if (repeated || 0.5 * newell.norm() < 1e-6 * h * h) {
      ++s.degenerateFaces;
    } else if (newell.dot(normals) < 0) {
      ++s.flippedFaces;
    }
    if (n == 4 && len[1] + len[3] > 0 && len[0] + len[2] > 0) {
      const double r = (len[0] + len[2]) / (len[1] + len[3]);
      aspects.push_back(std::max(r, 1 / r));
    }
  }
  s.aspectMedian = percentile(aspects, 0.5);

  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (std::size_t v = 0; v < surface.positions.size() / 3; ++v)
    lo = lo.cwiseMin(point(surface.positions, v)), hi = hi.cwiseMax(point(surface.positions, v));
  const double diagonal = (hi - lo).norm();
  s.hausdorffRelative = diagonal > 0 && s.faces ? hausdorff(q, surface) / diagonal : 0;
  return s;
}

}  // namespace tvf
