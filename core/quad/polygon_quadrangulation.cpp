#include "quad/polygon_quadrangulation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_set>
#include <utility>
#include <vector>

namespace tvf {
namespace {

uint64_t edgeKey(int32_t a, int32_t b) {
  const auto lo = static_cast<uint32_t>(std::min(a, b)), hi = static_cast<uint32_t>(std::max(a, b));
  return (static_cast<uint64_t>(lo) << 32) | hi;
}

// Per vertex, its number of edges, and whether it is on the mesh's boundary (an edge with one face).
struct Valences {
  std::vector<int32_t> valence;
  std::vector<uint8_t> onBoundary;
  std::unordered_set<uint64_t> edges;
};

Valences valences(const QuadMesh& m) {
  std::vector<uint64_t> keys;
  keys.reserve(m.faceVertices.size());
  for (int32_t f = 0; f < m.numFaces(); ++f)
    for (int32_t k = m.faceStart[f]; k < m.faceStart[f + 1]; ++k) {
      const int32_t next = k + 1 < m.faceStart[f + 1] ? k + 1 : m.faceStart[f];
      keys.push_back(edgeKey(m.faceVertices[k], m.faceVertices[next]));
    }
  std::sort(keys.begin(), keys.end());
  Valences out;
  out.valence.assign(m.numVertices(), 0);
  out.onBoundary.assign(m.numVertices(), 0);
  out.edges.reserve(keys.size());
  for (std::size_t k = 0; k < keys.size();) {
    std::size_t end = k;
    while (end < keys.size() && keys[end] == keys[k]) ++end;
    const auto a = static_cast<int32_t>(keys[k] >> 32), b = static_cast<int32_t>(keys[k] & 0xffffffffu);
    ++out.valence[a], ++out.valence[b];
    if (end - k == 1) out.onBoundary[a] = out.onBoundary[b] = 1;
    out.edges.insert(keys[k]);
    k = end;
  }
  return out;
}

// One polygon's search over its splits. Corners are the polygon's own indices 0..n-1; a range (i, j) is the
// sub-polygon i, i+1, ..., j closed by the chord (j, i) (the whole polygon: (0, n-1), closed by its own
// edge). Its part on that closing edge is a quad (i, a, b, j), or (once, in an odd polygon) a triangle.
class Splitter {
 public:
  Splitter(std::vector<Eigen::Vector2d> p, std::vector<Eigen::Vector3d> x,
           std::vector<Eigen::Vector3d> normal, std::vector<int32_t> baseValence,
           std::vector<uint8_t> chordAllowed)
      : p_(std::move(p)),
        x_(std::move(x)),
        normal_(std::move(normal)),
        n_(static_cast<int>(p_.size())),
        base_(std::move(baseValence)),
        allowed_(std::move(chordAllowed)),
        chords_(n_, 0) {
    double perimeter = 0;
    for (int k = 0; k < n_; ++k) perimeter += (p_[(k + 1) % n_] - p_[k]).norm();
    const double side = perimeter / n_;
    tiny_ = 1e-6 * side * side;
  }

  // The best split's parts (corner indices; a triangle's fourth is -1), empty when none is valid.
  std::vector<std::array<int, 4>> best(int* irregular) {
    std::vector<std::pair<int, int>> pending{{0, n_ - 1}};
    expand(pending, n_ % 2);
    *irregular = bestIrregular_;
    return bestParts_;
  }

 private:
  static constexpr long kMostLeaves = 400000;

  bool chord(int i, int j) const { return allowed_[static_cast<std::size_t>(i) * n_ + j] != 0; }

  struct PartCost {
    bool valid = false;
    int reflex = 0;    // corners turning right: a quad with one is a dart
    double angle = 0;  // the corners' departure from square (radians), quads only
  };

  // A part is valid when it is counter-clockwise and simple in the polygon's plane (a quad may have one
  // reflex corner when the diagonal from it leaves two counter-clockwise triangles: a dart) and its vector
  // area faces the surface's side at every corner (where the polygon is curved, or folds over a crease).
  PartCost partCost(const std::array<int, 4>& part) const {
    const int k = part[3] < 0 ? 3 : 4;
    auto area2 = [&](int a, int b, int c) {
      const Eigen::Vector2d u = p_[part[b]] - p_[part[a]], w = p_[part[c]] - p_[part[a]];
      return u.x() * w.y() - u.y() * w.x();
    };
    PartCost out;
    const bool simple = k == 3 ? area2(0, 1, 2) > tiny_
                               : (area2(0, 1, 2) > tiny_ && area2(0, 2, 3) > tiny_) ||
                                     (area2(0, 1, 3) > tiny_ && area2(1, 2, 3) > tiny_);
    if (!simple) return out;
    Eigen::Vector3d vectorArea = Eigen::Vector3d::Zero();
    for (int c = 0; c < k; ++c) vectorArea += x_[part[c]].cross(x_[part[(c + 1) % k]]);
    for (int c = 0; c < k; ++c) {
      if (!(vectorArea.dot(normal_[part[c]]) > 0)) return out;
      const Eigen::Vector2d in = p_[part[c]] - p_[part[(c + k - 1) % k]],
                            on = p_[part[(c + 1) % k]] - p_[part[c]];
      const double turn = in.x() * on.y() - in.y() * on.x();
      out.reflex += turn < 0;
      if (k == 4) out.angle += std::abs(std::atan2(turn, in.dot(on)) - M_PI / 2);
    }
    out.valid = true;
    return out;
  }

  void place(std::vector<std::pair<int, int>>& pending, int trianglesLeft, const std::array<int, 4>& part,
             const std::vector<std::pair<int, int>>& ranges) {
    const PartCost cost = partCost(part);
    if (!cost.valid) return;
    int odd = 0;
    for (const auto& [i, j] : pending) odd += (j - i + 1) % 2;
    for (const auto& [i, j] : ranges) {
      if (j - i >= 2 && !chord(i, j)) return;
      odd += (j - i + 1) % 2;
    }
    if (odd > trianglesLeft) return;
    const std::size_t size = pending.size();
    for (const auto& [i, j] : ranges)
      if (j - i >= 2) pending.push_back({i, j}), ++chords_[i], ++chords_[j];
    parts_.push_back(part);
    angleCost_ += cost.angle, reflex_ += cost.reflex;
    expand(pending, trianglesLeft);
    angleCost_ -= cost.angle, reflex_ -= cost.reflex;
    parts_.pop_back();
    for (const auto& [i, j] : ranges)
      if (j - i >= 2) --chords_[i], --chords_[j];
    pending.resize(size);
  }

  void expand(std::vector<std::pair<int, int>>& pending, int trianglesLeft) {
    if (leaves_ > kMostLeaves) return;
    if (pending.empty()) {
      ++leaves_;
      // A dart counts as an irregular corner: it is taken only where it spares one.
      int irregular = reflex_;
      for (int v = 0; v < n_; ++v) irregular += base_[v] >= 0 && base_[v] + chords_[v] != 4;
      if (irregular < bestIrregular_ || (irregular == bestIrregular_ && angleCost_ < bestAngle_))
        bestIrregular_ = irregular, bestAngle_ = angleCost_, bestParts_ = parts_;
      return;
    }
    const auto [i, j] = pending.back();
    pending.pop_back();
    for (int a = i + 1; a < j; ++a) {
      if (trianglesLeft > 0) place(pending, trianglesLeft - 1, {i, a, j, -1}, {{i, a}, {a, j}});
      for (int b = a + 1; b < j; ++b) place(pending, trianglesLeft, {i, a, b, j}, {{i, a}, {a, b}, {b, j}});
    }
    pending.push_back({i, j});
  }

  std::vector<Eigen::Vector2d> p_;
  std::vector<Eigen::Vector3d> x_, normal_;  // the corners on the surface, and its unit normal there
  int n_;
  std::vector<int32_t> base_;  // per corner its valence, -1 on the boundary (not counted)
  std::vector<uint8_t> allowed_;
  std::vector<int> chords_;
  std::vector<std::array<int, 4>> parts_, bestParts_;
  double angleCost_ = 0, bestAngle_ = 1e300, tiny_ = 0;
  int bestIrregular_ = 1 << 30, reflex_ = 0;
  long leaves_ = 0;
};

// The polygon's corners in the plane of its Newell normal, counter-clockwise as seen along it.
std::vector<Eigen::Vector2d> projected(const QuadMesh& m, const int32_t* corner, int n) {
  auto x = [&](int k) { return Eigen::Vector3d(&m.positions[3 * corner[k % n]]); };
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) normal += x(k).cross(x(k + 1));
  normal.normalize();
  Eigen::Vector3d e1 = (x(1) - x(0)) - (x(1) - x(0)).dot(normal) * normal;
  e1.normalize();
  const Eigen::Vector3d e2 = normal.cross(e1);
  std::vector<Eigen::Vector2d> out(n);
  for (int k = 0; k < n; ++k) out[k] = {(x(k) - x(0)).dot(e1), (x(k) - x(0)).dot(e2)};
  return out;
}

// The input surface's unit normal at each corner of a polygon (that of the input face it lies in).
std::vector<Eigen::Vector3d> surfaceNormals(const QuadMesh& m, const SurfaceMesh& surface,
                                            const int32_t* corner, int n) {
  std::vector<Eigen::Vector3d> out(n);
  for (int k = 0; k < n; ++k) {
    const int32_t* t = &surface.triangles[3 * m.vertexFace[corner[k]]];
    const Eigen::Vector3d a(&surface.positions[3 * t[0]]), b(&surface.positions[3 * t[1]]),
        c(&surface.positions[3 * t[2]]);
    out[k] = (b - a).cross(c - a).normalized();
  }
  return out;
}

}  // namespace

int32_t quadrangulatePolygons(QuadMesh& m, const SurfaceMesh& surface) {
  // Most meshes have no polygon to split: then the edge table is not built at all.
  auto splittable = [&](int32_t f) {
    const int32_t n = m.faceStart[f + 1] - m.faceStart[f];
    return n >= 6 && n <= kLargestQuadrangulatedPolygon;
  };
  bool any = false;
  for (int32_t f = 0; f < m.numFaces() && !any; ++f) any = splittable(f);
  if (!any) return 0;
  Valences v = valences(m);
  std::vector<int32_t> start{0}, corners;
  corners.reserve(m.faceVertices.size());
  int32_t split = 0;
  for (int32_t f = 0; f < m.numFaces(); ++f) {
    const int32_t* c = &m.faceVertices[m.faceStart[f]];
    const int n = m.faceStart[f + 1] - m.faceStart[f];
    std::vector<std::array<int, 4>> parts;
    // A polygon with a vertex twice is kept: a part could hold it twice (degenerate).
    auto repeats = [&] {
      std::vector<int32_t> distinct(c, c + n);
      std::sort(distinct.begin(), distinct.end());
      return std::adjacent_find(distinct.begin(), distinct.end()) != distinct.end();
    };
    if (splittable(f) && !repeats()) {
      std::vector<int32_t> base(n);
      int irregularNow = 0;
      for (int k = 0; k < n; ++k) {
        base[k] = v.onBoundary[c[k]] ? -1 : v.valence[c[k]];
        irregularNow += base[k] >= 0 && base[k] != 4;
      }
      // A chord may not join corners that are joined already (round the polygon's outside, or by a chord of a
      // polygon split before this one).
      std::vector<uint8_t> allowed(static_cast<std::size_t>(n) * n, 0);
      for (int i = 0; i < n; ++i)
        for (int j = i + 2; j < n; ++j)
          allowed[static_cast<std::size_t>(i) * n + j] =
              !(i == 0 && j == n - 1) && !v.edges.count(edgeKey(c[i], c[j]));
      int irregular = 0;
      std::vector<Eigen::Vector3d> x(n);
      for (int k = 0; k < n; ++k) x[k] = Eigen::Vector3d(&m.positions[3 * c[k]]);
      parts = Splitter(projected(m, c, n), std::move(x), surfaceNormals(m, surface, c, n), std::move(base),
                       std::move(allowed))
                  .best(&irregular);
      if (irregular > irregularNow) parts.clear();
    }
    if (parts.empty()) {
      corners.insert(corners.end(), c, c + n);
      start.push_back(static_cast<int32_t>(corners.size()));
      continue;
    }
    ++split;
    for (const std::array<int, 4>& part : parts) {
      // Its chords, for the polygons after it that share corners with it.
      for (int k = 0, size = part[3] < 0 ? 3 : 4; k < size; ++k) {
        const int32_t a = c[part[k]], b = c[part[(k + 1) % size]];
        if (v.edges.insert(edgeKey(a, b)).second) ++v.valence[a], ++v.valence[b];
      }
      for (int k = 0; k < 4 && part[k] >= 0; ++k) corners.push_back(c[part[k]]);
      start.push_back(static_cast<int32_t>(corners.size()));
    }
  }
  m.faceStart = std::move(start);
  m.faceVertices = std::move(corners);
  return split;
}

}  // namespace tvf
