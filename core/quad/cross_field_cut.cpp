#include "quad/cross_field_cut.h"

#include <cmath>
#include <queue>

#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

constexpr double kQuarter = 1.5707963267948966;

Eigen::Vector3d faceNormalOf(const MeshGeometry& g, int32_t f) {
  return Eigen::Vector3d(&g.faceNormal[3 * f]);
}

// The angle of x from the edge's direction, counter-clockwise about n.
double angleFromEdge(const Eigen::Vector3d& edge, const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
  return std::atan2(edge.cross(x).dot(n), edge.dot(x));
}

// Quarter turns r (0..3) with X_to ~ X_from carried across the edge and turned r quarters.
int8_t matchingAcross(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                      const std::vector<double>& x, int32_t e, int32_t from, int32_t to) {
  const Eigen::Vector3d edge = edgeVector(mesh, t, e);
  const double a = angleFromEdge(edge, Eigen::Vector3d(&x[3 * from]), faceNormalOf(g, from));
  const double b = angleFromEdge(edge, Eigen::Vector3d(&x[3 * to]), faceNormalOf(g, to));
  const long r = std::lround((b - a) / kQuarter);
  return static_cast<int8_t>(((r % 4) + 4) % 4);
}

// A unit direction in each face's plane: the field's, or the first edge's where the field vanishes.
std::vector<double> planarDirections(const SurfaceMesh& mesh, const MeshGeometry& g,
                                     const std::vector<double>& faceDirections) {
  const int32_t nf = static_cast<int32_t>(mesh.triangles.size() / 3);
  std::vector<double> x(3 * nf);
  for (int32_t f = 0; f < nf; ++f) {
    const Eigen::Vector3d n = faceNormalOf(g, f);
    Eigen::Vector3d d(&faceDirections[3 * f]);
    d -= n * n.dot(d);
    if (!(d.norm() > 1e-12) || !d.allFinite()) {
      Eigen::Vector3d p[3];
      facePositions(mesh, f, p);
      d = p[1] - p[0];
    }
    Eigen::Map<Eigen::Vector3d> xf(&x[3 * f]);
    xf = d.normalized();
  }
  return x;
}

// Breadth-first over the faces, each face reached turned to match the face it was reached from. Returns the
// spanning tree's edges (1 where the tree crosses the edge).
std::vector<uint8_t> combAlongTree(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                                   std::vector<double>& x) {
  std::vector<uint8_t> tree(t.numEdges, 0), seen(t.numFaces, 0);
  std::queue<int32_t> queue;
  for (int32_t seed = 0; seed < t.numFaces; ++seed) {
    if (seen[seed]) continue;
    seen[seed] = 1;
    queue.push(seed);
    while (!queue.empty()) {
      const int32_t f = queue.front();
      queue.pop();
      for (int c = 0; c < 3; ++c) {
        const int32_t e = t.edgeOf(f, c), h = t.otherFace(e, f);
        if (h < 0 || seen[h]) continue;
        seen[h] = 1;
        tree[e] = 1;
        const int r = matchingAcross(mesh, t, g, x, e, f, h);
        Eigen::Map<Eigen::Vector3d> xh(&x[3 * h]);
        xh = quarterTurned(Eigen::Vector3d(xh), faceNormalOf(g, h), 4 - r);
        queue.push(h);
      }
    }
  }
  return tree;
}

// The interior edges no tree edge crosses, less the branches that end at a vertex that is neither a cone nor
// on the boundary (round such a vertex the field closes up, so nothing needs cutting there).
std::vector<uint8_t> prunedCutGraph(const MeshTopology& t, const std::vector<uint8_t>& tree,
                                    const std::vector<uint8_t>& coneVertex) {
  std::vector<uint8_t> cut(t.numEdges, 0);
  std::vector<int32_t> degree(t.numVertices, 0);
  for (int32_t e = 0; e < t.numEdges; ++e) {
    if (tree[e] || t.isBoundaryEdge[e] || t.edgeFaceCount[e] != 2) continue;
    cut[e] = 1;
    ++degree[t.edgeVertices[2 * e]];
    ++degree[t.edgeVertices[2 * e + 1]];
  }
  std::vector<int32_t> leaves;
  // A branch that reaches the boundary ends there: the cut joins cones and handles to the boundary too.
  auto terminal = [&](int32_t v) { return coneVertex[v] || t.isBoundaryVertex[v]; };
  for (int32_t v = 0; v < t.numVertices; ++v)
    if (degree[v] == 1 && !terminal(v)) leaves.push_back(v);
  while (!leaves.empty()) {
    const int32_t v = leaves.back();
    leaves.pop_back();
    if (degree[v] != 1) continue;
    for (int32_t k = t.vertexEdgeStart[v]; k < t.vertexEdgeStart[v + 1]; ++k) {
      const int32_t e = t.vertexEdgeList[k];
      if (!cut[e]) continue;
      cut[e] = 0;
      --degree[v];
      const int32_t w = t.edgeVertices[2 * e] == v ? t.edgeVertices[2 * e + 1] : t.edgeVertices[2 * e];
      if (--degree[w] == 1 && !terminal(w)) leaves.push_back(w);
      break;
    }
  }
  return cut;
}

// The faces round vertex v from corner (f, c), counter-clockwise, each with the edge to the next. An open fan
// (v on the boundary) is walked from its first face, whichever corner it is reached from: its last edge then
// is a boundary edge.
void walkFan(const SurfaceMesh& mesh, const MeshTopology& t, int32_t f, int c, std::vector<int32_t>& faces,
             std::vector<int32_t>& edges) {
  faces.clear();
  edges.clear();
  const int32_t v = mesh.triangles[3 * f + c];
  // Clockwise (across the edge from v to the next corner) to the boundary, or round to f again when closed.
  const int32_t start = f;
  for (int32_t steps = 0; steps <= t.numFaces; ++steps) {
    const int32_t back = t.otherFace(t.edgeOf(f, c), f);
    if (back < 0) break;
    if (back == start) {
      f = start, c = mesh.cornerOf(start, v);
      break;
    }
    f = back, c = mesh.cornerOf(back, v);
  }
  int32_t face = f, corner = c;
  do {
    faces.push_back(face);
    const int32_t e = t.edgeOf(face, (corner + 2) % 3);
    edges.push_back(e);
    face = t.otherFace(e, face);
    if (face < 0) break;
    corner = mesh.cornerOf(face, v);
  } while (face != f && faces.size() <= static_cast<std::size_t>(t.numFaces));
}

// Quarter turns gained crossing edge e from face `from`.
int turnsCrossing(const CrossFieldCut& cut, const MeshTopology& t, int32_t e, int32_t from) {
  return t.edgeFaces[2 * e] == from ? cut.matching[e] : -cut.matching[e];
}

// The boundary's edges and the features', each with the coordinate constant along it in the face beside it.
std::vector<CrossFieldCut::IsoEdge> isoEdgesOf(const SurfaceMesh& mesh, const MeshTopology& t,
                                               const std::vector<double>& x, const MeshGeometry& g,
                                               const std::vector<int32_t>& featureEdges) {
  std::vector<uint8_t> wanted(t.numEdges, 0);
  for (int32_t e = 0; e < t.numEdges; ++e) wanted[e] = t.isBoundaryEdge[e];
  for (int32_t e : featureEdges)
    if (e >= 0 && e < t.numEdges) wanted[e] = 1;
  std::vector<CrossFieldCut::IsoEdge> out;
  for (int32_t e = 0; e < t.numEdges; ++e) {
    if (!wanted[e]) continue;
    const int32_t f = t.edgeFaces[2 * e] >= 0 ? t.edgeFaces[2 * e] : t.edgeFaces[2 * e + 1];
    if (f < 0) continue;
    const Eigen::Vector3d d = edgeVector(mesh, t, e), xf(&x[3 * f]);
    const Eigen::Vector3d yf = faceNormalOf(g, f).cross(xf);
    // Along X, u grows and v stays: v is the constant one.
    out.push_back({e, f, static_cast<int8_t>(std::abs(d.dot(xf)) >= std::abs(d.dot(yf)) ? 1 : 0)});
  }
  return out;
}

}  // namespace

Eigen::Vector3d quarterTurned(const Eigen::Vector3d& x, const Eigen::Vector3d& n, int quarters) {
  Eigen::Vector3d y = x;
  for (int k = 0; k < ((quarters % 4) + 4) % 4; ++k) y = n.cross(y);
  return y;
}

CrossFieldCut cutCrossField(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                            const std::vector<double>& faceDirections,
                            const std::vector<int32_t>& featureEdges) {
  CrossFieldCut out;
  out.direction = planarDirections(mesh, g, faceDirections);
  const std::vector<uint8_t> tree = combAlongTree(mesh, t, g, out.direction);
  out.matching.assign(t.numEdges, 0);
  for (int32_t e = 0; e < t.numEdges; ++e)
    if (t.edgeFaces[2 * e + 1] >= 0 && t.edgeFaces[2 * e] >= 0)
      out.matching[e] =
          matchingAcross(mesh, t, g, out.direction, e, t.edgeFaces[2 * e], t.edgeFaces[2 * e + 1]);

  // Fans and their turns first (the cones decide the pruning), copies after the cut is known. A fan's faces
  // go to fanFaceList, the edge from each to the next to fanEdges (same offsets).
  std::vector<uint8_t> cornerSeen(3 * t.numFaces, 0), coneVertex(t.numVertices, 0);
  std::vector<int32_t> faces, edges, fanEdges;
  out.fanFaceStart.push_back(0);
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int c = 0; c < 3; ++c) {
      if (cornerSeen[3 * f + c]) continue;
      walkFan(mesh, t, f, c, faces, edges);
      const int32_t v = mesh.triangles[3 * f + c];
      int turns = 0;
      const bool closed = t.otherFace(edges.back(), faces.back()) == faces.front();
      for (std::size_t k = 0; k < faces.size(); ++k) {
        cornerSeen[3 * faces[k] + mesh.cornerOf(faces[k], v)] = 1;
        if (closed || k + 1 < faces.size()) turns += turnsCrossing(out, t, edges[k], faces[k]);
      }
      turns = closed ? ((turns % 4) + 4) % 4 : 0;
      out.fanTurns.push_back(static_cast<int8_t>(turns));
      out.fanVertex.push_back(v);
      if (turns) coneVertex[v] = 1, ++out.cones;
      out.fanFaceList.insert(out.fanFaceList.end(), faces.begin(), faces.end());
      fanEdges.insert(fanEdges.end(), edges.begin(), edges.end());
      out.fanFaceStart.push_back(static_cast<int32_t>(out.fanFaceList.size()));
    }
  out.cut = prunedCutGraph(t, tree, coneVertex);
  for (uint8_t c : out.cut) out.cutEdges += c;

  // Copies: within a fan, a new one after each cut edge; the first starts after the fan's last cut edge.
  out.cornerCopy.assign(3 * t.numFaces, -1);
  out.fanFirstCopy.push_back(0);
  for (std::size_t fan = 0; fan + 1 < out.fanFaceStart.size(); ++fan) {
    const int32_t* fs = &out.fanFaceList[out.fanFaceStart[fan]];
    const int32_t* es = &fanEdges[out.fanFaceStart[fan]];
    const std::size_t m = out.fanFaceStart[fan + 1] - out.fanFaceStart[fan];
    // An open fan runs from one boundary edge to the other: its first copy starts at its first face.
    const bool open = t.isBoundaryEdge[es[m - 1]] != 0;
    std::size_t start = 0;
    for (std::size_t k = 0; k < m && !open; ++k)
      if (out.cut[es[k]]) start = (k + 1) % m;
    const int32_t first = static_cast<int32_t>(out.copyFan.size());
    auto newCopy = [&](int32_t edge, int32_t fromFace, int32_t previous) {
      out.copyFan.push_back(static_cast<int32_t>(fan));
      out.copyEdge.push_back(edge);
      out.copyFromFace.push_back(fromFace);
      out.copyPrevious.push_back(previous);
      return static_cast<int32_t>(out.copyFan.size()) - 1;
    };
    const std::size_t closing = (start + m - 1) % m;
    const bool anyCut = !open && out.cut[es[closing]] != 0;
    int32_t copy = newCopy(anyCut ? es[closing] : -1, anyCut ? fs[closing] : -1, first);
    const int32_t v = out.fanVertex[fan];
    for (std::size_t step = 0; step < m; ++step) {
      const std::size_t k = (start + step) % m;
      out.cornerCopy[3 * fs[k] + mesh.cornerOf(fs[k], v)] = copy;
      if (step + 1 < m && out.cut[es[k]]) copy = newCopy(es[k], fs[k], copy);
    }
    if (anyCut) out.copyPrevious[first] = copy;
    out.fanFirstCopy.push_back(static_cast<int32_t>(out.copyFan.size()));
  }
  out.isoEdges = isoEdgesOf(mesh, t, out.direction, g, featureEdges);
  return out;
}

}  // namespace tvf
