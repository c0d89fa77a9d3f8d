#include "mesh/feature_edges.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/angles.h"
#include "common/input_error.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

void checkAngle(double degrees) {
  if (!(degrees >= 0 && degrees <= 180))
    throw InputError("the feature angle must be a number of degrees in [0, 180], not " +
                     std::to_string(degrees));
}

std::string pairName(const VertexPair& pair) {
  return "[" + std::to_string(pair[0]) + ", " + std::to_string(pair[1]) + "]";
}

// The interior edge a user's pair names; the boundary edges are the boundary condition's to direct.
int32_t pairEdge(const MeshTopology& t, const VertexPair& pair, const char* role) {
  const int32_t e = findEdge(t, pair[0], pair[1]);
  if (e < 0)
    throw InputError(std::string("the feature edge to ") + role + " " + pairName(pair) +
                     " is not a mesh edge");
  if (t.isBoundaryEdge[e])
    throw InputError(std::string("the feature edge to ") + role + " " + pairName(pair) +
                     " is a boundary edge: the boundary condition directs the field there");
  return e;
}

// The angle between the normals, by atan2 so that small folds keep their precision (acos loses it near 0).
double foldAngle(const MeshGeometry& g, int32_t f, int32_t h) {
  const double* a = &g.faceNormal[3 * f];
  const double* b = &g.faceNormal[3 * h];
  const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

int32_t otherVertex(const MeshTopology& t, int32_t e, int32_t v) {
  return t.edgeVertices[2 * e] == v ? t.edgeVertices[2 * e + 1] : t.edgeVertices[2 * e];
}

// The feature edges at each vertex (CSR, each vertex's edges ascending since the input is).
struct FeatureStar {
  std::vector<int32_t> start, list;
  int32_t valence(int32_t v) const { return start[v + 1] - start[v]; }
};

FeatureStar featureStar(const MeshTopology& t, const std::vector<int32_t>& edges) {
  FeatureStar s;
  s.start.assign(t.numVertices + 1, 0);
  for (const int32_t e : edges)
    for (int k = 0; k < 2; ++k) ++s.start[t.edgeVertices[2 * e + k] + 1];
  for (int32_t v = 0; v < t.numVertices; ++v) s.start[v + 1] += s.start[v];
  s.list.resize(s.start.back());
  std::vector<int32_t> fill(s.start.begin(), s.start.end() - 1);
  for (const int32_t e : edges)
    for (int k = 0; k < 2; ++k) s.list[fill[t.edgeVertices[2 * e + k]]++] = e;
  return s;
}

// Walks from vertex `from` along `edge` while the walk passes through vertices of feature valence 2 and
// meets no edge already taken (which closes a loop).
FeatureCurve walkCurve(const MeshTopology& t, const FeatureStar& star, std::vector<uint8_t>& taken,
                       int32_t from, int32_t edge) {
  FeatureCurve curve;
  int32_t v = from, e = edge;
  while (true) {
    taken[e] = 1;
    curve.edges.push_back(e);
    curve.signs.push_back(t.edgeVertices[2 * e] == v ? 1 : -1);
    v = otherVertex(t, e, v);
    if (star.valence(v) != 2) return curve;
    const int32_t* next = &star.list[star.start[v]];
    const int32_t n = next[0] == e ? next[1] : next[0];
    if (taken[n]) {
      curve.closed = n == curve.edges.front();
      return curve;
    }
    e = n;
  }
}

}  // namespace

std::vector<int32_t> sharpEdges(const MeshTopology& t, const MeshGeometry& g, double degrees) {
  checkAngle(degrees);
  std::vector<int32_t> edges;
  if (degrees == 0) return edges;
  const double threshold = degrees * kPi / 180;
  for (int32_t e = 0; e < t.numEdges; ++e) {
    if (t.edgeFaceCount[e] != 2) continue;
    if (foldAngle(g, t.edgeFaces[2 * e], t.edgeFaces[2 * e + 1]) > threshold) edges.push_back(e);
  }
  return edges;
}

namespace {

double boundingDiagonal(const SurfaceMesh& m) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t i = 0; i < m.positions.size(); i += 3)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], m.positions[i + c]);
      hi[c] = std::max(hi[c], m.positions[i + c]);
    }
  double d2 = 0;
  for (int c = 0; c < 3; ++c) d2 += hi[c] > lo[c] ? (hi[c] - lo[c]) * (hi[c] - lo[c]) : 0;
  return std::sqrt(d2);
}

}  // namespace

FoldProfile foldProfile(const SurfaceMesh& m, const MeshTopology& t, const MeshGeometry& g) {
  const double flat = kFlatFoldDegrees * kPi / 180, sharp = kSharpFoldDegrees * kPi / 180;
  FoldProfile p;
  std::vector<int32_t> sharpList;
  for (int32_t e = 0; e < t.numEdges; ++e) {
    if (t.edgeFaceCount[e] != 2) continue;
    const double fold = foldAngle(g, t.edgeFaces[2 * e], t.edgeFaces[2 * e + 1]);
    if (!std::isfinite(fold)) continue;  // a degenerate face's normal
    ++p.interiorEdges;
    p.gradualEdges += fold > flat && fold <= sharp;
    if (fold > sharp) sharpList.push_back(e);
  }
  p.sharpEdges = static_cast<int32_t>(sharpList.size());
  const double longCurve = kLongCurveDiagonal * boundingDiagonal(m);
  for (const FeatureCurve& curve : featureCurves(t, sharpList)) {
    double length = 0;
    for (const int32_t e : curve.edges) length += edgeVector(m, t, e).norm();
    if (length >= longCurve) p.longCurveEdges += static_cast<int32_t>(curve.edges.size());
  }
  return p;
}

double suggestedFeatureAngle(const FoldProfile& p) {
  const double sharp = p.sharpShare(), onLongCurves = p.longCurveShare();
  const bool creased =
      p.sharpEdges > 0 && ((sharp >= kCreasedSharpShare && onLongCurves >= kSomeLongCurveShare) ||
                           onLongCurves >= kCreasedLongCurveShare);
  return creased ? kSharpFoldDegrees : 0;
}

std::vector<int32_t> featureEdges(const MeshTopology& t, const MeshGeometry& g, double degrees,
                                  const std::vector<VertexPair>& add, const std::vector<VertexPair>& remove) {
  std::vector<uint8_t> isFeature(t.numEdges, 0);
  for (const int32_t e : sharpEdges(t, g, degrees)) isFeature[e] = 1;
  // Every pair is checked before any is applied, so a refusal names the first bad pair whatever its list.
  std::vector<int32_t> added, removed;
  for (const VertexPair& p : add) added.push_back(pairEdge(t, p, "add"));
  for (const VertexPair& p : remove) removed.push_back(pairEdge(t, p, "remove"));
  for (const int32_t e : added) isFeature[e] = 1;
  for (const int32_t e : removed) isFeature[e] = 0;
  std::vector<int32_t> edges;
  for (int32_t e = 0; e < t.numEdges; ++e)
    if (isFeature[e]) edges.push_back(e);
  return edges;
}

std::vector<FeatureCurve> featureCurves(const MeshTopology& t, const std::vector<int32_t>& edges) {
  std::vector<int32_t> sorted(edges);
  for (const int32_t e : sorted)
    if (e < 0 || e >= t.numEdges)
      throw InputError("feature edge " + std::to_string(e) + " is not a mesh edge");
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  const FeatureStar star = featureStar(t, sorted);
  std::vector<uint8_t> taken(t.numEdges, 0);
  std::vector<FeatureCurve> curves;
  // Open curves first, from their ends (valence 1) and junctions (valence >= 3), in vertex order.
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (star.valence(v) == 2) continue;
    for (int32_t k = star.start[v]; k < star.start[v + 1]; ++k)
      if (!taken[star.list[k]]) curves.push_back(walkCurve(t, star, taken, v, star.list[k]));
  }
  // What is left runs through valence-2 vertices only: closed loops, each walked from its lowest edge's lower
  // vertex.
  for (const int32_t e : sorted)
    if (!taken[e]) curves.push_back(walkCurve(t, star, taken, t.edgeVertices[2 * e], e));
  return curves;
}

}  // namespace tvf
