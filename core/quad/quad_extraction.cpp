#include "quad/quad_extraction.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "mesh/mesh_geometry.h"
#include "quad/polygon_quadrangulation.h"

namespace tvf {
namespace {

struct Vec2 {
  double u, v;
};
Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.u - b.u, a.v - b.v};
}
Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.u + b.u, a.v + b.v};
}
double cross(Vec2 a, Vec2 b) {
  return a.u * b.v - a.v * b.u;
}

// The axis directions, counter-clockwise: +u, +v, -u, -v; a port of a regular grid point is one of them.
constexpr int kAxis[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
int axisIndex(int du, int dv) {
  for (int k = 0; k < 4; ++k)
    if (kAxis[k][0] == du && kAxis[k][1] == dv) return k;
  return -1;
}

struct GridPoint {
  int32_t face;      // the face it lies in (a cone: the first of its fan)
  int32_t fan = -1;  // a cone's fan, -1 inside a face
  double bary[3];
  long iu = 0, iv = 0;      // its (u, v) in its face's chart (inside a face)
  bool onBoundary = false;  // on the surface's boundary (an open fan's vertex, or on a boundary edge)
};

// A cone's port: the direction (du, dv) in `face`'s chart.
struct ConePort {
  int32_t face;
  int du, dv;
};

struct PortRef {
  int32_t point = -1;
  int port = -1;
  bool operator==(const PortRef& o) const { return point == o.point && port == o.port; }
};
// Where a port leads off the surface (out through its boundary, or the gap of a boundary vertex's fan).
constexpr PortRef kOutside{-2, -2};

class Extractor {
 public:
  Extractor(const SurfaceMesh& mesh, const MeshTopology& t, const CrossFieldCut& cut,
            const SeamlessParametrization& p)
      : mesh_(mesh),
        t_(t),
        cut_(cut),
        uv_(p.cornerUV),
        shift_(p.edgeShift),
        vertexPointAt_(3 * t.numFaces, -1) {}

  QuadExtraction run() {
    findVertexPoints();
    findFacePoints();
    traceAll();
    return assemble();
  }

 private:
  Vec2 corner(int32_t f, int k) const { return {uv_[6 * f + 2 * k], uv_[6 * f + 2 * k + 1]}; }
  // Barycentric coordinates of x in f's (u, v) triangle. Each is its edge's side of x (edgeSide), so a point
  // on an edge that two faces of a chart share is inside one of them, or on the edge in both: never in both
  // nor in neither, whatever the round-off of the corners (a grid point on a diagonal of a regular grid).
  void barycentric(int32_t f, Vec2 x, double l[3]) const {
    const double a = uvTwiceArea(uv_, f);
    for (int k = 0; k < 3; ++k) l[k] = edgeSide(corner(f, (k + 1) % 3), corner(f, (k + 2) % 3), x) / a;
  }

  // Twice the signed area of (p, q, x), computed from the lexicographically smaller end: for q, p the same
  // number negated, bit for bit (from p's end and from q's, round-off would differ).
  static double edgeSide(Vec2 p, Vec2 q, Vec2 x) {
    if (q.u < p.u || (q.u == p.u && q.v < p.v)) return -cross(p - q, x - q);
    return cross(q - p, x - p);
  }

  // Carries a point and a direction from f's chart into the chart of g across edge e.
  void carry(int32_t e, int32_t f, Vec2& x, int& du, int& dv, Vec2* target) const {
    if (!cut_.cut[e]) return;
    const int r = cut_.matching[e];
    const Vec2 s{shift_[2 * e], shift_[2 * e + 1]};
    auto apply = [&](Vec2 y, bool point) {
      Vec2 o;
      if (t_.edgeFaces[2 * e] == f) {
        quarterTurn2(-r, y.u, y.v, o.u, o.v);
        return point ? o + s : o;
      }
      quarterTurn2(r, point ? y.u - s.u : y.u, point ? y.v - s.v : y.v, o.u, o.v);
      return o;
    };
    x = apply(x, true);
    if (target) *target = apply(*target, true);
    const Vec2 d = apply({static_cast<double>(du), static_cast<double>(dv)}, false);
    du = static_cast<int>(std::lround(d.u));
    dv = static_cast<int>(std::lround(d.v));
  }

  // Vertices on grid points (cones, corners of features and of the boundary, whose (u, v) are whole by
  // construction, and a tessellation's vertices the grid runs through, whole by the solve's snapping): their
  // ports are the axis directions in their faces' wedges, counter-clockwise round the fan. A boundary
  // vertex's fan is open: the direction along its last edge is a port too, and a gap (kOutside) closes the
  // cycle.
  void findVertexPoints() {
    const int32_t numFans = static_cast<int32_t>(cut_.fanTurns.size());
    for (int32_t fan = 0; fan < numFans; ++fan) {
      const int32_t v = cut_.fanVertex[fan];
      if (!onGridPoint(cut_.fanFaceList[cut_.fanFaceStart[fan]], v)) continue;
      const int32_t last = cut_.fanFaceList[cut_.fanFaceStart[fan + 1] - 1];
      const bool open = t_.otherFace(t_.edgeOf(last, (mesh_.cornerOf(last, v) + 2) % 3), last) < 0;
      GridPoint p{cut_.fanFaceList[cut_.fanFaceStart[fan]], fan, {1, 0, 0}};
      p.onBoundary = open;
      const int32_t id = static_cast<int32_t>(points_.size());
      points_.push_back(p);
      ports_.emplace_back();
      std::vector<ConePort>& ports = conePorts_.emplace_back();
      for (int32_t k = cut_.fanFaceStart[fan]; k < cut_.fanFaceStart[fan + 1]; ++k) {
        const int32_t f = cut_.fanFaceList[k];
        const int c = mesh_.cornerOf(f, v);
        vertexPointAt_[3 * f + c] = id;
        const Vec2 o = corner(f, c), a = corner(f, (c + 1) % 3) - o, b = corner(f, (c + 2) % 3) - o;
        if (!(cross(a, b) > 0)) continue;  // a flipped face's wedge holds no port
        const bool closesFan = open && f == last;
        std::vector<std::pair<double, int>> inWedge;
        for (int d = 0; d < 4; ++d) {
          const Vec2 dir{static_cast<double>(kAxis[d][0]), static_cast<double>(kAxis[d][1])};
          const bool fromA = cross(a, dir) > 0 || (cross(a, dir) == 0 && a.u * dir.u + a.v * dir.v > 0);
          const bool toB =
              cross(dir, b) > 0 || (closesFan && cross(dir, b) == 0 && b.u * dir.u + b.v * dir.v > 0);
          if (fromA && toB) inWedge.emplace_back(std::atan2(cross(a, dir), a.u * dir.u + a.v * dir.v), d);
        }
        std::sort(inWedge.begin(), inWedge.end());
        for (const auto& [angle, d] : inWedge) ports.push_back({f, kAxis[d][0], kAxis[d][1]});
      }
      ports_.back().assign(ports.size(), PortRef{});
      if (open) {
        ports.push_back({-1, 0, 0});
        ports_.back().push_back(kOutside);
      }
    }
  }

  // Whether vertex v's (u, v) in face f are both whole.
  bool onGridPoint(int32_t f, int32_t v) const {
    const Vec2 q = corner(f, mesh_.cornerOf(f, v));
    return q.u == std::round(q.u) && q.v == std::round(q.v);
  }

  void findFacePoints() {
    faceFirstPoint_.assign(t_.numFaces + 1, 0);
    for (int32_t f = 0; f < t_.numFaces; ++f) {
      faceFirstPoint_[f] = static_cast<int32_t>(points_.size());
      if (!(uvTwiceArea(uv_, f) > 0)) continue;
      double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
      for (int k = 0; k < 3; ++k) {
        const Vec2 q = corner(f, k);
        lo[0] = std::min(lo[0], q.u), hi[0] = std::max(hi[0], q.u);
        lo[1] = std::min(lo[1], q.v), hi[1] = std::max(hi[1], q.v);
      }
      for (long i = static_cast<long>(std::ceil(lo[0])); i <= static_cast<long>(std::floor(hi[0])); ++i)
        for (long j = static_cast<long>(std::ceil(lo[1])); j <= static_cast<long>(std::floor(hi[1])); ++j)
          addIfInside(f, i, j);
    }
    faceFirstPoint_[t_.numFaces] = static_cast<int32_t>(points_.size());
  }

  void addIfInside(int32_t f, long i, long j) {
    double l[3];
    barycentric(f, {static_cast<double>(i), static_cast<double>(j)}, l);
    int zeros = 0;
    for (int k = 0; k < 3; ++k) {
      if (l[k] < 0) return;
      if (l[k] == 0) {
        ++zeros;
        // On an edge: the point belongs to the edge's first face.
        const int32_t e = t_.edgeOf(f, (k + 1) % 3);
        if (t_.edgeFaces[2 * e] != f) return;
      }
    }
    if (zeros > 1) return;  // a corner: only vertices on grid points sit there, found with their fans
    GridPoint p{f, -1, {l[0], l[1], l[2]}, i, j};
    for (int k = 0; k < 3; ++k) p.onBoundary |= l[k] == 0 && t_.isBoundaryEdge[t_.edgeOf(f, (k + 1) % 3)];
    points_.push_back(p);
    ports_.emplace_back(4, PortRef{});
  }

  // The grid point at integer (u, v) `x` of f's chart, or -1.
  int32_t pointAt(int32_t f, Vec2 x) const {
    const long i = std::lround(x.u), j = std::lround(x.v);
    for (int32_t k = faceFirstPoint_[f]; k < faceFirstPoint_[f + 1]; ++k)
      if (points_[k].iu == i && points_[k].iv == j) return k;
    return -1;
  }

  // The port of cone `id` leaving along (du, dv) in f's chart; -1 when f's wedge does not hold it.
  int conePort(int32_t id, int32_t f, int du, int dv) const {
    const std::vector<ConePort>& ports = conePorts_[id];
    for (std::size_t k = 0; k < ports.size(); ++k)
      if (ports[k].face == f && ports[k].du == du && ports[k].dv == dv) return static_cast<int>(k);
    return -1;
  }

  // Arrival at cone `id` through face f heading (du, dv): the port back along the walk. When the walk came
  // in along an edge of f, the port lies in a neighbour of the fan.
  PortRef arriveAtCone(int32_t id, int32_t f, int du, int dv) const {
    int port = conePort(id, f, -du, -dv);
    if (port >= 0) return {id, port};
    for (int c = 0; c < 3; ++c) {
      const int32_t e = t_.edgeOf(f, c), g = t_.otherFace(e, f);
      if (g < 0) continue;
      Vec2 x{0, 0};
      int bu = -du, bv = -dv;
      carry(e, f, x, bu, bv, nullptr);
      port = conePort(id, g, bu, bv);
      if (port >= 0) return {id, port};
    }
    return {};
  }

  // Walks from x in f along (du, dv) to the grid point at `target`: the port it arrives through.
  PortRef trace(int32_t f, Vec2 x, int du, int dv, Vec2 target) const {
    const int maxSteps = 64 + 4 * static_cast<int>(std::sqrt(static_cast<double>(t_.numFaces)));
    for (int step = 0; step < maxSteps; ++step) {
      for (int k = 0; k < 3; ++k) {
        const Vec2 q = corner(f, k);
        const int32_t cone = vertexPointAt_[3 * f + k];
        if (cone >= 0 && std::abs(q.u - target.u) < 1e-6 && std::abs(q.v - target.v) < 1e-6)
          return arriveAtCone(cone, f, du, dv);
      }
      double lt[3], lx[3];
      barycentric(f, target, lt);
      if (lt[0] >= -1e-12 && lt[1] >= -1e-12 && lt[2] >= -1e-12) return arriveAtPoint(f, target, du, dv, lt);
      barycentric(f, x, lx);
      int exit = -1;
      double best = 1e300;
      for (int k = 0; k < 3; ++k) {
        if (!(lt[k] < 0)) continue;
        const double s = std::max(0.0, lx[k]) / (std::max(0.0, lx[k]) - lt[k]);
        if (s < best) best = s, exit = k;
      }
      if (exit < 0) return {};
      const int32_t e = t_.edgeOf(f, (exit + 1) % 3), g = t_.otherFace(e, f);
      // Straight out through the boundary the point lies on: a port off the surface, not a failed walk.
      if (g < 0) return step == 0 && best == 0 ? kOutside : PortRef{};
      x = x + Vec2{best * (target.u - x.u), best * (target.v - x.v)};
      carry(e, f, x, du, dv, &target);
      f = g;
    }
    return {};
  }

  PortRef arriveAtPoint(int32_t f, Vec2 target, int du, int dv, const double lt[3]) const {
    int32_t id = pointAt(f, target);
    if (id >= 0) return {id, axisIndex(-du, -dv)};
    // On an edge: the point was given to the face across it.
    for (int k = 0; k < 3; ++k) {
      if (std::abs(lt[k]) > 1e-9) continue;
      const int32_t e = t_.edgeOf(f, (k + 1) % 3), g = t_.otherFace(e, f);
      if (g < 0) continue;
      Vec2 x = target;
      int bu = du, bv = dv;
      carry(e, f, x, bu, bv, nullptr);
      id = pointAt(g, {std::round(x.u), std::round(x.v)});
      if (id >= 0) return {id, axisIndex(-bu, -bv)};
    }
    return {};
  }

  void traceAll() {
    for (int32_t id = 0; id < static_cast<int32_t>(points_.size()); ++id) {
      const GridPoint& p = points_[id];
      for (std::size_t port = 0; port < ports_[id].size(); ++port) {
        if (ports_[id][port] == kOutside) continue;
        int32_t f;
        int du, dv;
        Vec2 x;
        if (p.fan >= 0) {
          const ConePort& c = conePorts_[id][port];
          f = c.face, du = c.du, dv = c.dv;
          const int k = mesh_.cornerOf(f, cut_.fanVertex[p.fan]);
          x = corner(f, k);
          x = {std::round(x.u), std::round(x.v)};
        } else {
          f = p.face, du = kAxis[port][0], dv = kAxis[port][1];
          x = {static_cast<double>(p.iu), static_cast<double>(p.iv)};
        }
        ports_[id][port] = trace(f, x, du, dv, {x.u + du, x.v + dv});
        if (ports_[id][port].point == -1) ++failedTraces_;
      }
    }
  }

  QuadExtraction assemble() {
    QuadExtraction out;
    out.failedTraces = failedTraces_;
    // An edge is kept only when both its walks found each other.
    auto linked = [&](PortRef a) {
      const PortRef b = ports_[a.point][a.port];
      return b.point >= 0 && b.port >= 0 && ports_[b.point][b.port] == a;
    };
    std::vector<std::vector<uint8_t>> used(points_.size());
    for (std::size_t id = 0; id < points_.size(); ++id) used[id].assign(ports_[id].size(), 0);
    std::vector<int32_t> remap(points_.size(), -1), loop;
    for (int32_t id = 0; id < static_cast<int32_t>(points_.size()); ++id)
      for (int port = 0; port < static_cast<int>(ports_[id].size()); ++port) {
        if (used[id][port] || !linked({id, port})) continue;
        loop.clear();
        PortRef h{id, port};
        bool closed = false;
        bool outside = false;
        for (int k = 0; k < 16 && !(outside = ports_[h.point][h.port] == kOutside) && linked(h) &&
                        !used[h.point][h.port];
             ++k) {
          used[h.point][h.port] = 1;
          loop.push_back(h.point);
          const PortRef b = ports_[h.point][h.port];
          const int valence = static_cast<int>(ports_[b.point].size());
          h = {b.point, (b.port + valence - 1) % valence};
          if (h == PortRef{id, port}) {
            closed = true;
            break;
          }
        }
        if (!closed || loop.size() < 3) {
          if (!outside) ++out.openLoops;  // round the outside of the boundary: no face there
          continue;
        }
        for (int32_t v : loop) {
          if (remap[v] < 0) remap[v] = addVertex(out.mesh, v);
          out.mesh.faceVertices.push_back(remap[v]);
        }
        out.mesh.faceStart.push_back(static_cast<int32_t>(out.mesh.faceVertices.size()));
      }
    out.mesh.faceStart.insert(out.mesh.faceStart.begin(), 0);
    std::vector<uint8_t> vertexOnBoundary(out.mesh.numVertices(), 0);
    for (std::size_t id = 0; id < points_.size(); ++id)
      if (remap[id] >= 0) vertexOnBoundary[remap[id]] = points_[id].onBoundary;
    out.filledHoles = fillHoles(out.mesh, vertexOnBoundary);
    removeSpikes(out.mesh);
    out.splitPolygons = quadrangulatePolygons(out.mesh, mesh_);
    return out;
  }

  // Where the grid folds, a walk can come back along the edge it left by (a point with one linked port): the
  // face's loop holds a, b, a. The spike is cut off (the face keeps its other corners; a vertex left in no
  // face is dropped), so that no face has a vertex twice.
  static void removeSpikes(QuadMesh& m) {
    std::vector<int32_t> start{0}, vertices, loop;
    for (int32_t f = 0; f < m.numFaces(); ++f) {
      loop.assign(m.faceVertices.begin() + m.faceStart[f], m.faceVertices.begin() + m.faceStart[f + 1]);
      for (std::size_t i = 0; loop.size() >= 3 && i < loop.size();) {
        const std::size_t n = loop.size(), before = (i + n - 1) % n, after = (i + 1) % n;
        if (loop[before] != loop[after]) {
          ++i;
          continue;
        }
        // Drop b (at i) and the second a (at after).
        const std::size_t first = std::max(i, after), second = std::min(i, after);
        loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(first));
        loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(second));
        i = 0;
      }
      if (loop.size() < 3) continue;
      vertices.insert(vertices.end(), loop.begin(), loop.end());
      start.push_back(static_cast<int32_t>(vertices.size()));
    }
    if (vertices.size() == m.faceVertices.size()) return;
    std::vector<int32_t> index(m.numVertices(), -1);
    QuadMesh out;
    for (int32_t& v : vertices) {
      if (index[v] < 0) {
        index[v] = out.numVertices();
        out.positions.insert(out.positions.end(), m.positions.begin() + 3 * v,
                             m.positions.begin() + 3 * v + 3);
        out.vertexFace.push_back(m.vertexFace[v]);
      }
      v = index[v];
    }
    out.faceStart = std::move(start);
    out.faceVertices = std::move(vertices);
    m = std::move(out);
  }

  // Where walks failed the quad mesh has holes; each hole bounded by at most kLongestHole edges becomes one
  // polygon, so that the mesh is closed as the surface is (the polygons are counted, not hidden: they lower
  // the quad share).
  static int32_t fillHoles(QuadMesh& m, const std::vector<uint8_t>& onBoundary) {
    constexpr std::size_t kLongestHole = 64;
    std::set<std::pair<int32_t, int32_t>> directed;
    for (int32_t f = 0; f < m.numFaces(); ++f)
      for (int32_t k = m.faceStart[f]; k < m.faceStart[f + 1]; ++k) {
        const int32_t next = k + 1 < m.faceStart[f + 1] ? k + 1 : m.faceStart[f];
        directed.insert({m.faceVertices[k], m.faceVertices[next]});
      }
    // The holes' edges, each the reverse of a face's edge that has no twin.
    std::multimap<int32_t, int32_t> hole;
    for (const auto& [a, b] : directed)
      if (!directed.count({b, a})) hole.insert({b, a});
    int32_t filled = 0;
    auto fill = [&](const std::vector<int32_t>& loop) {
      // The surface's own boundary is not a hole, nor is it where a quad beside it is missing (the loop round
      // the outside then detours inwards): a loop with two boundary points in a row runs along the boundary.
      bool alongBoundary = false;
      for (std::size_t k = 0; k < loop.size(); ++k)
        alongBoundary = alongBoundary || (onBoundary[loop[k]] && onBoundary[loop[(k + 1) % loop.size()]]);
      if (loop.size() < 3 || alongBoundary) return;
      m.faceVertices.insert(m.faceVertices.end(), loop.begin(), loop.end());
      m.faceStart.push_back(static_cast<int32_t>(m.faceVertices.size()));
      ++filled;
    };
    // Each walk along the holes' edges closes a loop whenever it comes back to a vertex it passed: a hole
    // that touches itself at a vertex (a figure 8) is two polygons, none with a vertex twice.
    std::vector<int32_t> path;
    while (!hole.empty()) {
      auto it = hole.begin();
      path.assign(1, it->first);
      int32_t at = it->second;
      hole.erase(it);
      for (;;) {
        const auto seen = std::find(path.begin(), path.end(), at);
        if (seen != path.end()) {
          fill(std::vector<int32_t>(seen, path.end()));
          path.erase(seen + 1, path.end());
        } else {
          path.push_back(at);
        }
        if (path.size() > kLongestHole) break;
        const auto next = hole.find(at);
        if (next == hole.end()) break;
        at = next->second;
        hole.erase(next);
      }
    }
    return filled;
  }

  int32_t addVertex(QuadMesh& q, int32_t id) const {
    const GridPoint& p = points_[id];
    Eigen::Vector3d x;
    if (p.fan >= 0) {
      x = vertexPosition(mesh_, cut_.fanVertex[p.fan]);
    } else {
      Eigen::Vector3d c[3];
      facePositions(mesh_, p.face, c);
      x = p.bary[0] * c[0] + p.bary[1] * c[1] + p.bary[2] * c[2];
    }
    q.positions.insert(q.positions.end(), {x.x(), x.y(), x.z()});
    q.vertexFace.push_back(p.face);
    return q.numVertices() - 1;
  }

  const SurfaceMesh& mesh_;
  const MeshTopology& t_;
  const CrossFieldCut& cut_;
  const std::vector<double>& uv_;
  const std::vector<double>& shift_;
  std::vector<GridPoint> points_;
  std::vector<std::vector<PortRef>> ports_;       // per point and port: where its iso-line arrives
  std::vector<std::vector<ConePort>> conePorts_;  // per vertex point (the first points), counter-clockwise
  std::vector<int32_t> vertexPointAt_;            // per face corner: its vertex point, -1 elsewhere
  std::vector<int32_t> faceFirstPoint_;
  int32_t failedTraces_ = 0;
};

}  // namespace

QuadExtraction extractQuads(const SurfaceMesh& mesh, const MeshTopology& topology, const CrossFieldCut& cut,
                            const SeamlessParametrization& parametrization) {
  return Extractor(mesh, topology, cut, parametrization).run();
}

}  // namespace tvf
