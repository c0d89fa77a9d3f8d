// SPDX-License-Identifier: GPL-2.0-or-later
#include "texture/texture_atlas.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <mutex>
#include <numeric>
#include <queue>
#include <tuple>
#include <utility>

#include "common/sparse_matrix.h"
#include "common/thread_team.h"
#include "mesh/mesh_geometry.h"
#include "solver/spd_solve.h"

namespace tvf {
namespace {

// Normal cone of a chart: a face joins while its normal is within ~66 degrees of the chart's mean normal.
// LSCM flattens such a patch with little area distortion; wider cones leave more charts to split.
constexpr double kConeCos = 0.0;
// ... and the length of the area-weighted mean normal must stay above this share of the chart's area.
constexpr double kMinMeanNormal = 0.75;
// A chart is split when, inside it, the area-weighted 95th / 5th percentile of the texel density exceeds
// this.
constexpr double kMaxDensityRatio = 1.8;
// A failed chart's piece of at least this many faces, too spread on its map (keepPiecesOnMap), is split at
// once.
constexpr size_t kSplitAtOnceFaces = 2000;
// Chart positions are searched on a grid of at most this many blocks per side.
constexpr int kPackGrid = 256;
// The density search stops when the densest packing found and the least dense failure are this close.
constexpr double kDensityPrecision = 1.004;
constexpr int kBisections = 6;
// Quarter turns tried per chart (8 or 16 angles packed no better on the test models, at 2-4x the time).
constexpr int kRotations = 4;

// What chart growth and flattening read per face and edge, over the mesh's own topology.
struct FaceGeometry {
  const MeshTopology& topology;
  std::vector<Eigen::Vector3d> normals, centroids;
  std::vector<double> areas;
  std::vector<double> edgeLength;  // per edge
};

FaceGeometry faceGeometry(const SurfaceMesh& mesh, const MeshTopology& t) {
  FaceGeometry g{t, {}, {}, {}, {}};
  g.normals.resize(t.numFaces);
  g.centroids.resize(t.numFaces);
  g.areas.resize(t.numFaces);
  for (int32_t f = 0; f < t.numFaces; ++f) {
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    const FaceNormalArea face = faceNormalArea(p);
    g.areas[f] = face.area;
    g.normals[f] = face.normal;
    g.centroids[f] = (p[0] + p[1] + p[2]) / 3;
  }
  g.edgeLength.resize(t.numEdges);
  for (int32_t e = 0; e < t.numEdges; ++e) g.edgeLength[e] = edgeVector(mesh, t, e).norm();
  return g;
}

// The face across corner k's edge (v_k -> v_k+1) of face f, or -1 at a boundary or non-manifold edge: charts
// grow only across edges where the surface is a surface.
int32_t neighbour(const MeshTopology& t, int32_t f, int k) {
  const int32_t e = t.edgeOf(f, k);
  return t.edgeFaceCount[e] == 2 ? t.otherFace(e, f) : -1;
}

// Corner k's edge length.
double cornerEdgeLength(const FaceGeometry& g, int32_t f, int k) {
  return g.edgeLength[g.topology.edgeOf(f, k)];
}

// Chart borders shortened: a face moves to a neighbouring chart when it shares more edge length with that
// chart than with its own and its normal is within the cone around that chart's mean normal. Growth in
// distance order leaves ragged, saw-toothed borders on meshes of long thin triangles; every tooth costs
// texels of border and gutter in the atlas and makes charts pack worse. Each move shortens the total border,
// so the passes end. Charts are then split into connected pieces.
void smoothChartBorders(const FaceGeometry& g, std::vector<int32_t>& chartOf,
                        std::vector<std::vector<int32_t>>& charts) {
  const MeshTopology& t = g.topology;
  const int32_t nF = static_cast<int32_t>(chartOf.size());
  std::vector<Eigen::Vector3d> normalSum(charts.size(), Eigen::Vector3d::Zero());
  for (int32_t f = 0; f < nF; ++f)
    if (chartOf[f] >= 0) normalSum[chartOf[f]] += g.normals[f] * g.areas[f];
  // Only a face next to another chart can move, and a face becomes one only when a neighbour moves: the
  // passes visit those alone, in the same order (armadillo-sub2: 65k of its 832k faces; 269 -> 161 ms).
  std::vector<uint8_t> mayMove(nF, 0);
  for (int32_t f = 0; f < nF; ++f)
    for (int k = 0; k < 3 && chartOf[f] >= 0; ++k) {
      const int32_t across = neighbour(t, f, k);
      if (across >= 0 && chartOf[across] >= 0 && chartOf[across] != chartOf[f]) mayMove[f] = 1;
    }
  for (int pass = 0; pass < 16; ++pass) {
    int moves = 0;
    for (int32_t f = 0; f < nF; ++f) {
      if (!mayMove[f]) continue;
      const int32_t own = chartOf[f];
      if (own < 0) continue;
      int32_t nb[3];
      double shared[3] = {0, 0, 0}, ownShared = 0;
      for (int k = 0; k < 3; ++k) {
        const int32_t across = neighbour(t, f, k);
        nb[k] = across >= 0 ? chartOf[across] : -1;
        if (nb[k] == own) ownShared += cornerEdgeLength(g, f, k);
      }
      int best = -1;
      for (int k = 0; k < 3; ++k) {
        if (nb[k] < 0 || nb[k] == own) continue;
        for (int j = 0; j < 3; ++j)
          if (nb[j] == nb[k]) shared[k] += cornerEdgeLength(g, f, j);
        if (shared[k] > ownShared * (1 + 1e-9) && (best < 0 || shared[k] > shared[best])) {
          const Eigen::Vector3d& n = normalSum[nb[k]];
          if (g.normals[f].dot(n) > kConeCos * n.norm()) best = k;
        }
      }
      if (best < 0) continue;
      normalSum[own] -= g.normals[f] * g.areas[f];
      normalSum[nb[best]] += g.normals[f] * g.areas[f];
      chartOf[f] = nb[best];
      ++moves;
      for (int k = 0; k < 3; ++k)
        if (const int32_t across = neighbour(t, f, k); across >= 0) mayMove[across] = 1;
    }
    if (moves == 0) break;
  }
  std::vector<uint8_t> seen(nF, 0);
  std::vector<std::vector<int32_t>> pieces;
  for (int32_t f = 0; f < nF; ++f) {
    if (chartOf[f] < 0 || seen[f]) continue;
    std::vector<int32_t> piece{f};
    seen[f] = 1;
    for (size_t h = 0; h < piece.size(); ++h)
      for (int k = 0; k < 3; ++k) {
        const int32_t o = neighbour(t, piece[h], k);
        if (o >= 0 && !seen[o] && chartOf[o] == chartOf[f]) seen[o] = 1, piece.push_back(o);
      }
    pieces.push_back(std::move(piece));
  }
  charts = std::move(pieces);
}

// Charts grown from seeds (largest faces first) in order of centroid distance from the seed, taking a face
// while its normal stays within the cone around the chart's area-weighted mean normal.
std::vector<std::vector<int32_t>> growCharts(const FaceGeometry& g) {
  const int32_t nF = static_cast<int32_t>(g.areas.size());
  std::vector<int32_t> chartOf(nF, -1), order;
  for (int32_t f = 0; f < nF; ++f)
    if (g.areas[f] > 0) order.push_back(f);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return g.areas[a] > g.areas[b]; });
  std::vector<std::vector<int32_t>> charts;
  using Item = std::pair<double, int32_t>;
  for (int32_t seed : order) {
    if (chartOf[seed] >= 0) continue;
    const int32_t id = static_cast<int32_t>(charts.size());
    std::vector<int32_t> members;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double area = 0;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> front;
    front.push({0.0, seed});
    while (!front.empty()) {
      const auto [d, f] = front.top();
      front.pop();
      if (chartOf[f] >= 0) continue;
      if (!members.empty()) {
        if (g.normals[f].dot(sum / sum.norm()) < kConeCos) continue;
        // The normals must not spread so far that their mean shrinks (a band around a tube would close).
        const Eigen::Vector3d next = sum + g.normals[f] * g.areas[f];
        if (next.norm() < kMinMeanNormal * (area + g.areas[f])) continue;
      }
      chartOf[f] = id;
      members.push_back(f);
      area += g.areas[f];
      sum += g.normals[f] * g.areas[f];
      for (int k = 0; k < 3; ++k) {
        const int32_t h = neighbour(g.topology, f, k);
        if (h >= 0 && chartOf[h] < 0 && g.areas[h] > 0)
          front.push({d + (g.centroids[h] - g.centroids[f]).norm(), h});
      }
    }
    charts.push_back(std::move(members));
  }
  smoothChartBorders(g, chartOf, charts);
  return charts;
}

// A chart's faces with their flattened corners (6 per face, same order as `faces`).
struct Chart {
  std::vector<int32_t> faces;
  std::vector<double> uv;
  std::vector<int32_t>
      boundary;  // corners 3j + k whose edge (to corner k + 1) no other face of the chart has
  double surfaceArea = 0;
  double spread =
      0;  // the area-weighted 95th / 5th percentile texel density ratio, once chartAcceptable measured it
};

// The corners whose edges bound the faces (3j + k for corner k of faces[j], the edge from it to the next).
std::vector<int32_t> boundaryCorners(const MeshTopology& t, const std::vector<int32_t>& faces) {
  std::vector<std::pair<int32_t, int32_t>> all;  // (edge, corner)
  all.reserve(3 * faces.size());
  for (size_t j = 0; j < faces.size(); ++j)
    for (int k = 0; k < 3; ++k) all.emplace_back(t.edgeOf(faces[j], k), static_cast<int32_t>(3 * j + k));
  std::sort(all.begin(), all.end());
  std::vector<int32_t> out;
  for (size_t i = 0; i < all.size();) {
    size_t j = i;
    while (j < all.size() && all[j].first == all[i].first) ++j;
    if (j - i == 1) out.push_back(all[i].second);
    i = j;
  }
  return out;
}

double signedArea2(const double* t) {
  return (t[2] - t[0]) * (t[5] - t[1]) - (t[4] - t[0]) * (t[3] - t[1]);
}

// The face laid flat in its own plane: corner 0 at the origin, corner 1 on the x axis, y = normal x x.
void inPlaneCorners(const Eigen::Vector3d p[3], const Eigen::Vector3d& normal, Eigen::Vector2d q[3]) {
  const Eigen::Vector3d e1 = p[1] - p[0];
  const double l1 = e1.norm();
  const Eigen::Vector3d x = e1 / l1, y = normal.cross(x);
  q[0] = {0, 0};
  q[1] = {l1, 0};
  q[2] = {(p[2] - p[0]).dot(x), (p[2] - p[0]).dot(y)};
}

// A face's two Cauchy-Riemann residuals (rot90(grad u) - grad v = 0, weighted by sqrt(area)) as linear
// forms: for corner k, its free column (or -1 when pinned) and its coefficients on u and v per residual; the
// pinned corners' part summed into `constant`.
struct FaceResidual {
  int32_t column[3];
  double cu[3][2], cv[3][2], constant[2];
};

// `local`: chart vertex of each mesh vertex; `column`: free column of each chart vertex, or -1 where pinned
// at pinnedAt(chart vertex).
template <class PinnedAt>
std::vector<FaceResidual> conformalResiduals(const SurfaceMesh& mesh, const FaceGeometry& g,
                                             const std::vector<int32_t>& faces,
                                             const std::vector<int32_t>& local,
                                             const std::vector<int32_t>& column, PinnedAt pinnedAt) {
  std::vector<FaceResidual> out(faces.size());
  for (size_t j = 0; j < faces.size(); ++j) {
    const int32_t f = faces[j];
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    Eigen::Vector2d q[3];
    inPlaneCorners(p, g.normals[f], q);
    const double w = 1.0 / (2.0 * std::sqrt(g.areas[f]));
    FaceResidual& r = out[j];
    r.constant[0] = r.constant[1] = 0;
    for (int k = 0; k < 3; ++k) {
      // Edge opposite corner k, counter-clockwise: grad u = sum_k u_k rot90(e_k) / 2A.
      const Eigen::Vector2d& a = q[(k + 1) % 3];
      const Eigen::Vector2d& b = q[(k + 2) % 3];
      const double ex = b.x() - a.x(), ey = b.y() - a.y();
      const int32_t i = local[mesh.triangles[3 * f + k]];
      // rot90(grad u) - grad v = (-sum u_k e_k - sum v_k rot90(e_k)) / 2A, rot90(e) = (-ey, ex).
      r.cu[k][0] = -ex * w, r.cu[k][1] = -ey * w;
      r.cv[k][0] = ey * w, r.cv[k][1] = -ex * w;
      r.column[k] = column[i];
      if (column[i] < 0) {
        const Eigen::Vector2d pv = pinnedAt(i);
        for (int t = 0; t < 2; ++t) r.constant[t] += r.cu[k][t] * pv.x() + r.cv[k][t] * pv.y();
      }
    }
  }
  return out;
}

// The normal equations' matrix of the residuals, upper triangle, unknowns interleaved: the pattern is each
// free vertex's free neighbours (itself included) in the chart, 2 x 2 blocks; every face adds its residual
// rows' outer products into the blocks of its corner pairs.
SparseMatrix conformalNormalEquations(const std::vector<FaceResidual>& residuals, int32_t nFree) {
  // Per free vertex, the free vertices at or below it that share a face with it (sorted, unique).
  std::vector<int32_t> start(nFree + 1, 0);
  for (const FaceResidual& r : residuals)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (r.column[a] >= 0 && r.column[b] >= 0 && r.column[a] <= r.column[b]) ++start[r.column[b] + 1];
  for (int32_t c = 0; c < nFree; ++c) start[c + 1] += start[c];
  std::vector<int32_t> below(start[nFree]), fill(start.begin(), start.end() - 1);
  for (const FaceResidual& r : residuals)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (r.column[a] >= 0 && r.column[b] >= 0 && r.column[a] <= r.column[b])
          below[fill[r.column[b]]++] = r.column[a];
  std::vector<int32_t> count(nFree);
  for (int32_t c = 0; c < nFree; ++c) {
    const auto first = below.begin() + start[c], last = below.begin() + start[c + 1];
    std::sort(first, last);
    count[c] = static_cast<int32_t>(std::unique(first, last) - first);
  }
  // Column 2c (u_c): rows 2a, 2a + 1 of each neighbour a < c, then 2c. Column 2c + 1: the same and 2c + 1.
  SparseMatrix upper(2 * nFree, 2 * nFree);
  int* outer = upper.outerIndexPtr();
  outer[0] = 0;
  for (int32_t c = 0; c < nFree; ++c) {
    outer[2 * c + 1] = outer[2 * c] + 2 * count[c] - 1;
    outer[2 * c + 2] = outer[2 * c + 1] + 2 * count[c];
  }
  upper.resizeNonZeros(outer[2 * nFree]);
  int* inner = upper.innerIndexPtr();
  double* value = upper.valuePtr();
  std::fill(value, value + outer[2 * nFree], 0.0);
  for (int32_t c = 0; c < nFree; ++c)
    for (int side = 0; side < 2; ++side) {
      int* rows = inner + outer[2 * c + side];
      for (int32_t k = 0; k < count[c]; ++k) {
        const int32_t a = below[start[c] + k];
        *rows++ = 2 * a;
        if (a != c || side == 1) *rows++ = 2 * a + 1;
      }
    }
  // The entry (x, y), x <= y, of unknowns x of vertex a and y of vertex b (a <= b): b's block column, a's
  // place.
  const auto at = [&](int32_t a, int32_t b, int ya, int yb) -> double& {
    const int32_t* first = below.data() + start[b];
    const int32_t k = static_cast<int32_t>(std::lower_bound(first, first + count[b], a) - first);
    return value[outer[2 * b + yb] + 2 * k + ya];
  };
  for (const FaceResidual& r : residuals)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int32_t a = r.column[i], b = r.column[j];
        if (a < 0 || b < 0 || a > b) continue;
        const double* coef[2][2] = {{r.cu[i], r.cv[i]}, {r.cu[j], r.cv[j]}};
        for (int ya = 0; ya < 2; ++ya)
          for (int yb = 0; yb < 2; ++yb) {
            if (a == b && ya > yb) continue;  // the diagonal block's lower half
            at(a, b, ya, yb) += coef[0][ya][0] * coef[1][yb][0] + coef[0][ya][1] * coef[1][yb][1];
          }
      }
  return upper;
}

// The normal equations' right-hand side: the residuals' pinned part moved across.
Eigen::VectorXd conformalRightHandSide(const std::vector<FaceResidual>& residuals, int32_t nFree) {
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * nFree);
  for (const FaceResidual& r : residuals)
    for (int k = 0; k < 3; ++k)
      if (r.column[k] >= 0)
        for (int t = 0; t < 2; ++t) {
          rhs[2 * r.column[k]] -= r.cu[k][t] * r.constant[t];
          rhs[2 * r.column[k] + 1] -= r.cv[k][t] * r.constant[t];
        }
  return rhs;
}

// Least-squares conformal map of the faces (Levy et al. 2002) with two far-apart vertices pinned. In each
// face's own orthonormal frame the map's gradients must satisfy grad v = rot90(grad u) (Cauchy-Riemann,
// orientation preserving); each face contributes those two residuals weighted by sqrt(area). Returns false if
// the solve fails.
// `local`: one entry per mesh vertex, all -1, left so (a chart's scratch, not remade per chart: at 832k faces
// clearing one per chart cost more than many charts' solves).
bool lscm(const SurfaceMesh& mesh, const FaceGeometry& g, Chart& chart, std::vector<int32_t>& local) {
  std::vector<int32_t> verts;
  struct Reset {
    std::vector<int32_t>& local;
    const std::vector<int32_t>& verts;
    ~Reset() {
      for (int32_t v : verts) local[v] = -1;
    }
  } reset{local, verts};
  for (int32_t f : chart.faces)
    for (int k = 0; k < 3; ++k) {
      const int32_t v = mesh.triangles[3 * f + k];
      if (local[v] < 0) local[v] = static_cast<int32_t>(verts.size()), verts.push_back(v);
    }
  const int32_t n = static_cast<int32_t>(verts.size());
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int32_t v : verts) centre += vertexPosition(mesh, v) / static_cast<double>(n);
  auto farthestFrom = [&](const Eigen::Vector3d& p) {
    int32_t best = 0;
    double bestD = -1;
    for (int32_t i = 0; i < n; ++i) {
      const double d = (vertexPosition(mesh, verts[i]) - p).norm();
      if (d > bestD) bestD = d, best = i;
    }
    return best;
  };
  const int32_t pinA = farthestFrom(centre);
  const int32_t pinB = farthestFrom(vertexPosition(mesh, verts[pinA]));
  const double span = (vertexPosition(mesh, verts[pinA]) - vertexPosition(mesh, verts[pinB])).norm();
  if (pinA == pinB || !(span > 0)) return false;
  // Unknowns: (u, v) of free vertex c at 2c and 2c + 1 (the matrix is then the chart's vertex graph in 2 x 2
  // blocks, its pattern read from the faces); pinned values move to the right-hand side.
  std::vector<int32_t> column(n, -1);
  int32_t nFree = 0;
  for (int32_t i = 0; i < n; ++i)
    if (i != pinA && i != pinB) column[i] = nFree++;
  const Eigen::Vector2d pinned[2] = {{0, 0}, {span, 0}};
  const std::vector<FaceResidual> residuals = conformalResiduals(
      mesh, g, chart.faces, local, column, [&](int32_t i) { return pinned[i == pinA ? 0 : 1]; });
  chart.uv.assign(6 * chart.faces.size(), 0.0);
  std::vector<Eigen::Vector2d> uvOf(n, Eigen::Vector2d::Zero());
  uvOf[pinA] = pinned[0];
  uvOf[pinB] = pinned[1];
  if (nFree > 0) {
    Eigen::VectorXd x;
    if (!solveSpdOnce(conformalNormalEquations(residuals, nFree), conformalRightHandSide(residuals, nFree),
                      x))
      return false;
    for (int32_t i = 0; i < n; ++i)
      if (column[i] >= 0) uvOf[i] = {x[2 * column[i]], x[2 * column[i] + 1]};
  }
  for (size_t j = 0; j < chart.faces.size(); ++j)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d& p = uvOf[local[mesh.triangles[3 * chart.faces[j] + k]]];
      chart.uv[6 * j + 2 * k] = p.x();
      chart.uv[6 * j + 2 * k + 1] = p.y();
    }
  return true;
}

// Area-weighted quantiles of values, at each of qs (ascending), sorting them once.
template <size_t N>
std::array<double, N> weightedQuantiles(std::vector<std::pair<double, double>> valueWeight,
                                        const std::array<double, N>& qs) {
  std::array<double, N> out{};
  if (valueWeight.empty()) return out;
  std::sort(valueWeight.begin(), valueWeight.end());
  double total = 0;
  for (const auto& [v, w] : valueWeight) total += w;
  double acc = 0;
  size_t k = 0;
  for (const auto& [v, w] : valueWeight) {
    acc += w;
    for (; k < N && acc >= qs[k] * total; ++k) out[k] = v;
  }
  for (; k < N; ++k) out[k] = valueWeight.back().first;
  return out;
}

// Whether the flattened chart covers some point twice. Its faces keep their orientation (checked first), so
// it does exactly when two of its boundary edges cross or touch away from a shared vertex. Boundary edges are
// bucketed on a grid of about one edge length; exact for any resolution the chart is later drawn at.
bool selfOverlaps(const SurfaceMesh& mesh, const Chart& chart) {
  struct Edge {
    int32_t a, b;  // mesh vertices
    Eigen::Vector2d p, q;
  };
  std::vector<Edge> edges;
  double length = 0;
  for (const int32_t c : chart.boundary) {
    const size_t face = c / 3, k = c % 3, k1 = (k + 1) % 3;
    Edge e{mesh.triangles[3 * chart.faces[face] + k],
           mesh.triangles[3 * chart.faces[face] + k1],
           {chart.uv[6 * face + 2 * k], chart.uv[6 * face + 2 * k + 1]},
           {chart.uv[6 * face + 2 * k1], chart.uv[6 * face + 2 * k1 + 1]}};
    length += std::hypot(e.q.x() - e.p.x(), e.q.y() - e.p.y());
    edges.push_back(e);
  }
  if (edges.size() < 3) return false;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Edge& e : edges)
    for (const Eigen::Vector2d& v : {e.p, e.q})
      x0 = std::min(x0, v.x()), y0 = std::min(y0, v.y()), x1 = std::max(x1, v.x()), y1 = std::max(y1, v.y());
  const double cell = std::max({length / edges.size(), (x1 - x0) / 1024, (y1 - y0) / 1024, 1e-300});
  const int nx = static_cast<int>((x1 - x0) / cell) + 1, ny = static_cast<int>((y1 - y0) / cell) + 1;
  std::vector<std::vector<int32_t>> bucket(static_cast<size_t>(nx) * ny);
  auto orient = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  };
  // c collinear with a-b: between them?
  auto onSegment = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
           std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
  };
  auto meet = [&](const Edge& e, const Edge& f) {
    const bool shareA = e.a == f.a || e.a == f.b, shareB = e.b == f.a || e.b == f.b;
    if (shareA && shareB) return false;
    if (shareA ||
        shareB) {  // adjacent along the boundary: they meet elsewhere only if collinear and folded back
      const Eigen::Vector2d& s = shareA ? e.p : e.q;
      const Eigen::Vector2d& eo = shareA ? e.q : e.p;
      const Eigen::Vector2d& fo = (f.a == (shareA ? e.a : e.b)) ? f.q : f.p;
      if (orient(s, eo, fo) != 0) return false;
      return (eo.x() - s.x()) * (fo.x() - s.x()) + (eo.y() - s.y()) * (fo.y() - s.y()) > 0;
    }
    const double d1 = orient(f.p, f.q, e.p), d2 = orient(f.p, f.q, e.q), d3 = orient(e.p, e.q, f.p),
                 d4 = orient(e.p, e.q, f.q);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
    return (d1 == 0 && onSegment(f.p, f.q, e.p)) || (d2 == 0 && onSegment(f.p, f.q, e.q)) ||
           (d3 == 0 && onSegment(e.p, e.q, f.p)) || (d4 == 0 && onSegment(e.p, e.q, f.q));
  };
  for (size_t i = 0; i < edges.size(); ++i) {
    const Edge& e = edges[i];
    const int cx0 = static_cast<int>((std::min(e.p.x(), e.q.x()) - x0) / cell),
              cx1 = static_cast<int>((std::max(e.p.x(), e.q.x()) - x0) / cell);
    const int cy0 = static_cast<int>((std::min(e.p.y(), e.q.y()) - y0) / cell),
              cy1 = static_cast<int>((std::max(e.p.y(), e.q.y()) - y0) / cell);
    for (int cy = cy0; cy <= std::min(cy1, ny - 1); ++cy)
      for (int cx = cx0; cx <= std::min(cx1, nx - 1); ++cx) {
        std::vector<int32_t>& b = bucket[static_cast<size_t>(cy) * nx + cx];
        for (int32_t o : b)
          if (meet(e, edges[o])) return true;
        b.push_back(static_cast<int32_t>(i));
      }
  }
  return false;
}

// Whether a flattened chart can be used as it is: no flipped triangle, a bounded density spread, no overlap.
// Finds the chart's boundary on the way.
bool chartAcceptable(const SurfaceMesh& mesh, Chart& chart, const FaceGeometry& g) {
  std::vector<std::pair<double, double>> density;
  for (size_t j = 0; j < chart.faces.size(); ++j) {
    const double a = signedArea2(&chart.uv[6 * j]) / 2;
    if (!(a > 0)) return false;  // flipped or degenerate
    density.push_back({std::sqrt(a / g.areas[chart.faces[j]]), g.areas[chart.faces[j]]});
  }
  if (chart.faces.size() == 1) {
    chart.boundary = {0, 1, 2};
    return true;
  }
  const auto [p05, p95] = weightedQuantiles(std::move(density), std::array<double, 2>{0.05, 0.95});
  chart.spread = p95 / p05;
  if (!(p95 <= kMaxDensityRatio * p05)) return false;
  chart.boundary = boundaryCorners(g.topology, chart.faces);
  return !selfOverlaps(mesh, chart);
}

// The cut between the halves (mark 1 and 2) of a chart being split, shortened as smoothChartBorders does: a
// plane cut through the faces is saw-toothed.
void shortenCut(const std::vector<int32_t>& faces, const FaceGeometry& g, std::vector<int32_t>& mark) {
  for (int pass = 0; pass < 16; ++pass) {
    int moves = 0;
    for (int32_t f : faces) {
      double len[3] = {0, 0, 0};
      for (int k = 0; k < 3; ++k) {
        const int32_t o = neighbour(g.topology, f, k);
        if (o >= 0 && (mark[o] == 1 || mark[o] == 2)) len[mark[o]] += cornerEdgeLength(g, f, k);
      }
      const int32_t other = 3 - mark[f];
      if (len[other] > len[mark[f]] * (1 + 1e-9)) mark[f] = other, ++moves;
    }
    if (moves == 0) break;
  }
}

// Splits faces in two at the median of their centroids along the longest axis of their spread, then into
// connected pieces.
std::vector<std::vector<int32_t>> splitFaces(const std::vector<int32_t>& faces, const FaceGeometry& g,
                                             std::vector<int32_t>& mark) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int32_t f : faces) mean += g.centroids[f] / static_cast<double>(faces.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int32_t f : faces) {
    const Eigen::Vector3d d = g.centroids[f] - mean;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d axis = eig.eigenvectors().col(2);
  std::vector<std::pair<double, int32_t>> keyed;
  for (int32_t f : faces) keyed.push_back({axis.dot(g.centroids[f]), f});
  std::sort(keyed.begin(), keyed.end());
  const size_t half = keyed.size() / 2;
  // mark: 1 + half index for faces of this chart, 0 elsewhere (restored before returning).
  const auto halve = [&] {
    for (size_t i = 0; i < keyed.size(); ++i) mark[keyed[i].second] = i < half ? 1 : 2;
  };
  halve();
  shortenCut(faces, g, mark);
  // Shortening can move every face back to one side; the split must make the pieces smaller, or the charting
  // loop would retry the same chart forever. The plain median cut always leaves two non-empty halves.
  const auto onSide = [&](int32_t side) {
    return std::count_if(faces.begin(), faces.end(), [&](int32_t f) { return mark[f] == side; });
  };
  if (onSide(1) == 0 || onSide(2) == 0) halve();
  std::vector<std::vector<int32_t>> pieces;
  for (const auto& kf : keyed) {
    const int32_t seed = kf.second;
    if (mark[seed] <= 0) continue;
    const int32_t side = mark[seed];
    std::vector<int32_t> piece{seed};
    mark[seed] = -side;
    for (size_t h = 0; h < piece.size(); ++h)
      for (int k = 0; k < 3; ++k) {
        const int32_t o = neighbour(g.topology, piece[h], k);
        if (o >= 0 && mark[o] == side) mark[o] = -side, piece.push_back(o);
      }
    pieces.push_back(std::move(piece));
  }
  for (int32_t f : faces) mark[f] = 0;
  return pieces;
}

// Convex hull of points (x, y pairs), counter-clockwise (Andrew's monotone chain).
std::vector<Eigen::Vector2d> convexHull(const std::vector<double>& xy) {
  std::vector<Eigen::Vector2d> p;
  for (size_t i = 0; i + 1 < xy.size(); i += 2) p.push_back({xy[i], xy[i + 1]});
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (!(b.x() < a.x()) && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// The rotation angle that makes the chart's bounding rectangle smallest (one hull edge is always on it).
double minimumRectangleAngle(const std::vector<double>& xy) {
  const std::vector<Eigen::Vector2d> hull = convexHull(xy);
  double bestArea = 1e300, bestAngle = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
    const double angle = std::atan2(b.y() - a.y(), b.x() - a.x());
    const double c = std::cos(angle), s = std::sin(angle);
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const Eigen::Vector2d& p : hull) {
      const double x = c * p.x() + s * p.y(), y = -s * p.x() + c * p.y();
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    if ((x1 - x0) * (y1 - y0) < bestArea) bestArea = (x1 - x0) * (y1 - y0), bestAngle = angle;
  }
  return bestAngle;
}

// Rotates the chart to its smallest bounding rectangle, moves its corner to the origin, and scales it to
// surface length units (UV area = surface area).
void normalizeChart(Chart& chart, const FaceGeometry& g) {
  double uvArea = 0;
  chart.surfaceArea = 0;
  for (size_t j = 0; j < chart.faces.size(); ++j) {
    uvArea += signedArea2(&chart.uv[6 * j]) / 2;
    chart.surfaceArea += g.areas[chart.faces[j]];
  }
  const double s = uvArea > 0 ? std::sqrt(chart.surfaceArea / uvArea) : 1.0;
  const double angle = minimumRectangleAngle(chart.uv);
  const double c = std::cos(angle), sn = std::sin(angle);
  const size_t m = chart.uv.size() / 2;
  double x0 = 1e300, y0 = 1e300;
  for (size_t i = 0; i < m; ++i) {
    const double x = chart.uv[2 * i], y = chart.uv[2 * i + 1];
    chart.uv[2 * i] = s * (c * x + sn * y);
    chart.uv[2 * i + 1] = s * (-sn * x + c * y);
    x0 = std::min(x0, chart.uv[2 * i]), y0 = std::min(y0, chart.uv[2 * i + 1]);
  }
  for (size_t i = 0; i < m; ++i) chart.uv[2 * i] -= x0, chart.uv[2 * i + 1] -= y0;
}

// The thread team's run for tasks that may throw (out of memory in a chart's solve or a packing's bitmaps,
// which the team's tasks must not): the first exception is rethrown here once every part has returned.
void runParts(int parts, const std::function<void(int)>& task) {
  std::exception_ptr failure;
  std::mutex m;
  ThreadTeam::shared().run(parts, [&](int part) {
    try {
      task(part);
    } catch (...) {
      std::lock_guard<std::mutex> lock(m);
      if (!failure) failure = std::current_exception();
    }
  });
  if (failure) std::rethrow_exception(failure);
}

// A chart flattened and checked, or, when its map is not acceptable, the pieces to try instead; of those, the
// ones that the failed map already serves are kept as charts on it.
struct ChartOutcome {
  Chart chart;
  bool accepted = false;
  std::vector<std::vector<int32_t>> pieces;
  std::vector<Chart> kept;
};

// What one thread needs to flatten charts: scratch the size of the mesh, cleared as it is used.
struct ChartScratch {
  std::vector<int32_t> vertexLocal, faceMark, pieceMark;
  explicit ChartScratch(const SurfaceMesh& mesh)
      : vertexLocal(mesh.numVertices(), -1), faceMark(mesh.numFaces(), 0), pieceMark(mesh.numFaces(), 0) {}
};

// The pieces of a chart whose map failed that are acceptable on that map, moved from out.pieces to out.kept.
// A conformal map restricted to a piece is a conformal map of the piece, face for face as conformal; a piece
// whose density spread and overlap pass on it needs no map of its own. A big piece whose spread on it is past
// the bound squared is split again at once: its own map would not pass either (of such pieces of 2,000 faces
// or more on six benchmark meshes, 2 in 40 did). `slot` and `mark`: one entry per mesh face, all 0, left so.
void keepPiecesOnMap(const SurfaceMesh& mesh, const FaceGeometry& g, const Chart& failed, ChartOutcome& out,
                     std::vector<int32_t>& slot, std::vector<int32_t>& mark) {
  for (size_t j = 0; j < failed.faces.size(); ++j) slot[failed.faces[j]] = static_cast<int32_t>(j) + 1;
  std::vector<std::vector<int32_t>> left;
  for (size_t w = 0; w < out.pieces.size(); ++w) {
    std::vector<int32_t> piece = std::move(out.pieces[w]);  // out.pieces grows below
    Chart chart;
    chart.uv.resize(6 * piece.size());
    for (size_t i = 0; i < piece.size(); ++i) {
      const double* from = &failed.uv[6 * static_cast<size_t>(slot[piece[i]] - 1)];
      std::copy(from, from + 6, &chart.uv[6 * i]);
    }
    chart.faces = std::move(piece);
    if (chartAcceptable(mesh, chart, g)) {
      normalizeChart(chart, g);
      out.kept.push_back(std::move(chart));
    } else if (chart.spread > kMaxDensityRatio * kMaxDensityRatio &&
               chart.faces.size() >= kSplitAtOnceFaces) {
      for (auto& half : splitFaces(chart.faces, g, mark)) out.pieces.push_back(std::move(half));
    } else {
      left.push_back(std::move(chart.faces));
    }
  }
  out.pieces = std::move(left);
  for (int32_t f : failed.faces) slot[f] = 0;
}

ChartOutcome flattenOrSplit(const SurfaceMesh& mesh, const FaceGeometry& g, std::vector<int32_t> faces,
                            ChartScratch& scratch) {
  ChartOutcome out;
  out.chart.faces = std::move(faces);
  Chart& chart = out.chart;
  const bool mapped = lscm(mesh, g, chart, scratch.vertexLocal);
  if (mapped && chartAcceptable(mesh, chart, g)) {
    normalizeChart(chart, g);
    out.accepted = true;
    return out;
  }
  if (chart.faces.size() == 1) {
    // A single face whose map failed (a sliver): its own shape in its plane.
    const int32_t f = chart.faces[0];
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    Eigen::Vector2d q[3];
    inPlaneCorners(p, g.normals[f], q);
    chart.uv = {q[0].x(), q[0].y(), q[1].x(), q[1].y(), q[2].x(), q[2].y()};
    chart.boundary = {0, 1, 2};
    normalizeChart(chart, g);
    out.accepted = true;
    return out;
  }
  out.pieces = splitFaces(chart.faces, g, scratch.faceMark);
  if (mapped) keepPiecesOnMap(mesh, g, chart, out, scratch.faceMark, scratch.pieceMark);
  return out;
}

// Flat charts covering every face of positive area: grown, flattened, split until acceptable. The charts of a
// round are independent: they are flattened on the thread team's parts (common/thread_team.h), biggest first,
// each part taking the next chart left; the pieces of those split make the next round. The result does not
// depend on the number of parts.
std::vector<Chart> makeCharts(const SurfaceMesh& mesh, const FaceGeometry& g, int& splits, int& keptPieces) {
  std::vector<std::vector<int32_t>> pending = growCharts(g);
  std::vector<Chart> charts;
  splits = keptPieces = 0;
  const int parts = ThreadTeam::usefulParts();
  std::vector<ChartScratch> scratch;
  for (int k = 0; k < parts; ++k) scratch.emplace_back(mesh);
  while (!pending.empty()) {
    std::stable_sort(pending.begin(), pending.end(),
                     [](const auto& a, const auto& b) { return a.size() > b.size(); });
    std::vector<ChartOutcome> outcome(pending.size());
    std::atomic<size_t> next{0};
    runParts(parts, [&](int part) {
      for (size_t i; (i = next.fetch_add(1)) < pending.size();)
        outcome[i] = flattenOrSplit(mesh, g, std::move(pending[i]), scratch[part]);
    });
    pending.clear();
    for (ChartOutcome& o : outcome) {
      if (o.accepted) {
        charts.push_back(std::move(o.chart));
        continue;
      }
      ++splits;
      keptPieces += static_cast<int>(o.kept.size());
      for (Chart& kept : o.kept) charts.push_back(std::move(kept));
      for (auto& piece : o.pieces) pending.push_back(std::move(piece));
    }
  }
  std::stable_sort(charts.begin(), charts.end(),
                   [](const Chart& a, const Chart& b) { return a.surfaceArea > b.surfaceArea; });
  return charts;
}

// ---- Packing
// -------------------------------------------------------------------------------------------------

// A texel bitmap, rows of 64-bit words; bit x of row y is texel (x, y).
struct Bitmap {
  int width = 0, height = 0, words = 0;
  std::vector<uint64_t> bits;
  Bitmap(int w, int h) : width(w), height(h), words((w + 63) / 64), bits(static_cast<size_t>(words) * h, 0) {}
  bool get(int x, int y) const { return bits[static_cast<size_t>(y) * words + (x >> 6)] >> (x & 63) & 1u; }
  void set(int x, int y) { bits[static_cast<size_t>(y) * words + (x >> 6)] |= uint64_t{1} << (x & 63); }
  // 64 texels of row y starting at x (zeros past the end).
  uint64_t window(int x, int y) const {
    const uint64_t* row = &bits[static_cast<size_t>(y) * words];
    const int i = x >> 6, off = x & 63;
    uint64_t w = i < words ? row[i] >> off : 0;
    if (off && i + 1 < words) w |= row[i + 1] << (64 - off);
    return w;
  }
};

// Squared distance from p to the segment a-b.
double segmentDistance2(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
  const double s = l2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / l2, 0.0, 1.0) : 0.0;
  const double ex = ax + s * dx - px, ey = ay + s * dy - py;
  return ex * ex + ey * ey;
}

// Which side of the line a -> b p lies on, evaluated with a and b in one fixed (lexicographic) order and the
// sign turned for the other: the two faces of a shared edge then get the same value with opposite signs.
double edgeSide(double ax, double ay, double bx, double by, double px, double py) {
  if (ax > bx || (ax == bx && ay > by)) return -edgeSide(bx, by, ax, ay, px, py);
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// Whether p lies in the triangle (6 coordinates), its edges included, in either orientation. Watertight: a
// point on or beside an edge two triangles share is in one of them (or both), never in neither.
bool inTriangle(double px, double py, const double* t) {
  const double s0 = edgeSide(t[0], t[1], t[2], t[3], px, py), s1 = edgeSide(t[2], t[3], t[4], t[5], px, py),
               s2 = edgeSide(t[4], t[5], t[0], t[1], px, py);
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

// A chart laid out in texels at one density and rotation: corner positions (texels, from the bitmap's origin)
// and the bitmap of the texels it owns: those its triangles cover, and its gutter.
struct ChartShape {
  std::vector<double> texel;  // 6 per face
  Bitmap mask{0, 0};
};

// Adds to `out` the square (Chebyshev) dilation of `in` by r texels (r < 64): rows, then columns, a word at a
// time.
void dilateInto(const Bitmap& in, int r, Bitmap& out) {
  const int h = in.height, words = in.words;
  const uint64_t lastWord = in.width % 64 ? (uint64_t{1} << (in.width % 64)) - 1 : ~uint64_t{0};
  Bitmap rows(in.width, h);
  for (int y = 0; y < h; ++y) {
    const uint64_t* src = &in.bits[static_cast<size_t>(y) * words];
    uint64_t* dst = &rows.bits[static_cast<size_t>(y) * words];
    for (int k = 0; k < words; ++k) {
      uint64_t acc = src[k];
      for (int d = 1; d <= r; ++d) {
        acc |= src[k] << d | src[k] >> d;
        if (k > 0) acc |= src[k - 1] >> (64 - d);
        if (k + 1 < words) acc |= src[k + 1] << (64 - d);
      }
      dst[k] = acc;
    }
    if (words) dst[words - 1] &= lastWord;
  }
  for (int y = 0; y < h; ++y) {
    uint64_t* dst = &out.bits[static_cast<size_t>(y) * words];
    for (int dy = std::max(0, y - r); dy <= std::min(h - 1, y + r); ++dy) {
      const uint64_t* src = &rows.bits[static_cast<size_t>(dy) * words];
      for (int k = 0; k < words; ++k) dst[k] |= src[k];
    }
  }
}

// The chart at `density`, unrotated. It is moved by whole texels only, so that a quarter turn of its bitmap
// is the bitmap of the quarter-turned chart (rotatedQuarter): the texel centres map onto texel centres, and
// packing rasterizes each chart once per density instead of once per rotation.
ChartShape chartShape(const Chart& chart, double density, int gutter) {
  ChartShape s;
  s.texel.resize(chart.uv.size());
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (size_t i = 0; i < chart.uv.size(); i += 2) {
    const double x = chart.uv[i] * density, y = chart.uv[i + 1] * density;
    s.texel[i] = x, s.texel[i + 1] = y;
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  const int margin = gutter + 1;
  const double sx = margin - std::floor(x0), sy = margin - std::floor(y0);
  for (size_t i = 0; i < s.texel.size(); i += 2) s.texel[i] += sx, s.texel[i + 1] += sy;
  const int w = static_cast<int>(std::ceil(x1 + sx)) + margin + 1;
  const int h = static_cast<int>(std::ceil(y1 + sy)) + margin + 1;
  // Touched: the texel's square meets a triangle (its centre within half a diagonal). Covered: its centre is
  // in a triangle (with a margin for the rounding of UVs to floats), i.e. the texels synthesis writes. The
  // chart does not overlap itself (chartAcceptable), so a centre outside its triangles is as far from the
  // chart as from its boundary's edges: those alone are measured, the triangles only rasterized.
  Bitmap touched(w, h), covered(w, h);
  constexpr double kReach = 0.70710678118654757 + 1e-6, kReach2 = 0.5 + 1e-9, kCoveredReach2 = 1e-6;
  for (size_t j = 0; j < s.texel.size(); j += 6) {
    const double* t = &s.texel[j];
    const int tx0 = std::max(0, static_cast<int>(std::ceil(std::min({t[0], t[2], t[4]}) - 0.5)));
    const int tx1 = std::min(w - 1, static_cast<int>(std::floor(std::max({t[0], t[2], t[4]}) - 0.5)));
    const int ty0 = std::max(0, static_cast<int>(std::ceil(std::min({t[1], t[3], t[5]}) - 0.5)));
    const int ty1 = std::min(h - 1, static_cast<int>(std::floor(std::max({t[1], t[3], t[5]}) - 0.5)));
    for (int y = ty0; y <= ty1; ++y)
      for (int x = tx0; x <= tx1; ++x)
        if (inTriangle(x + 0.5, y + 0.5, t)) covered.set(x, y), touched.set(x, y);
  }
  for (const int32_t c : chart.boundary) {
    const int k = c % 3;
    const double* a = &s.texel[2 * static_cast<size_t>(c)];
    const double* b = &s.texel[2 * static_cast<size_t>(c - k + (k + 1) % 3)];
    const int tx0 = std::max(0, static_cast<int>(std::floor(std::min(a[0], b[0]) - kReach - 0.5)));
    const int tx1 = std::min(w - 1, static_cast<int>(std::ceil(std::max(a[0], b[0]) + kReach - 0.5)));
    const int ty0 = std::max(0, static_cast<int>(std::floor(std::min(a[1], b[1]) - kReach - 0.5)));
    const int ty1 = std::min(h - 1, static_cast<int>(std::ceil(std::max(a[1], b[1]) + kReach - 0.5)));
    for (int y = ty0; y <= ty1; ++y)
      for (int x = tx0; x <= tx1; ++x) {
        if (covered.get(x, y)) continue;
        const double d2 = segmentDistance2(x + 0.5, y + 0.5, a[0], a[1], b[0], b[1]);
        if (d2 <= kReach2) touched.set(x, y);
        if (d2 <= kCoveredReach2) covered.set(x, y);
      }
  }
  // The chart owns its covered texels and `gutter` texels around them; the touched ring counts as the first
  // gutter texel rather than coming on top of the gutter (with no gutter, the touched texels stay its own so
  // that no texel is shared). Two charts' masks never overlap, so covered texels of different charts are more
  // than 2 * gutter texels apart and touched ones never share a texel.
  s.mask = Bitmap(w, h);
  dilateInto(covered, gutter, s.mask);
  dilateInto(touched, std::max(0, gutter - 1), s.mask);
  return s;
}

// The shape turned a quarter (x, y) -> (-y, x), kept in its bitmap: texel (i, j) goes to (h - 1 - j, i).
ChartShape rotatedQuarter(const ChartShape& in) {
  ChartShape s;
  const int w = in.mask.width, h = in.mask.height;
  s.texel.resize(in.texel.size());
  for (size_t i = 0; i < in.texel.size(); i += 2)
    s.texel[i] = h - in.texel[i + 1], s.texel[i + 1] = in.texel[i];
  s.mask = Bitmap(h, w);
  for (int y = 0; y < h; ++y)
    for (int k = 0; k < in.mask.words; ++k)
      for (uint64_t bits = in.mask.bits[static_cast<size_t>(y) * in.mask.words + k]; bits; bits &= bits - 1)
        s.mask.set(h - 1 - y, 64 * k + __builtin_ctzll(bits));
  return s;
}

bool fits(const Bitmap& atlas, const Bitmap& mask, int ox, int oy) {
  for (int y = 0; y < mask.height; ++y)
    for (int k = 0; k < mask.words; ++k) {
      const uint64_t m = mask.bits[static_cast<size_t>(y) * mask.words + k];
      if (m && (atlas.window(ox + 64 * k, oy + y) & m)) return false;
    }
  return true;
}

void stamp(Bitmap& atlas, const Bitmap& mask, int ox, int oy) {
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.get(x, y)) atlas.set(ox + x, oy + y);
}

struct Placement {
  int rotation = 0, x = 0, y = 0;
};

// The mask on a grid of b x b texel blocks (a block is taken when any of its texels is).
// Rows are ORed a block at a time, then each word's groups of b bits tested together (b is a power of two up
// to 64, as resolution / kPackGrid is).
Bitmap coarsen(const Bitmap& mask, int b) {
  Bitmap out((mask.width + b - 1) / b, (mask.height + b - 1) / b);
  const uint64_t group = b >= 64 ? ~uint64_t{0} : (uint64_t{1} << b) - 1;
  std::vector<uint64_t> rows(mask.words);
  for (int by = 0; by < out.height; ++by) {
    std::fill(rows.begin(), rows.end(), 0);
    for (int y = by * b; y < std::min(mask.height, (by + 1) * b); ++y)
      for (int k = 0; k < mask.words; ++k) rows[k] |= mask.bits[static_cast<size_t>(y) * mask.words + k];
    for (int k = 0; k < mask.words; ++k)
      for (int j = 0; j < 64 && rows[k] >> j; j += b)
        if (rows[k] >> j & group) out.set((64 * k + j) / b, by);
  }
  return out;
}

// First fit (lowest row, then column) of each chart, largest first, trying kRotations rotations and keeping
// the one whose top edge ends lowest. Positions are searched on a grid of `block` texels (the search costs
// the square of the grid size). Returns false when a chart does not fit.
bool pack(const std::vector<Chart>& charts, double density, int resolution, int gutter, int block,
          std::vector<Placement>& placements, std::vector<ChartShape>& shapes, double& used) {
  const int grid = resolution / block;
  Bitmap atlas(grid, grid);
  placements.assign(charts.size(), {});
  shapes.assign(charts.size(), {});
  for (size_t c = 0; c < charts.size(); ++c) {
    int bestTop = 1 << 30;
    Bitmap bestMask(0, 0);
    ChartShape turned = chartShape(charts[c], density, gutter);
    for (int rot = 0; rot < kRotations; ++rot) {
      ChartShape shape = rot == 0 ? turned : rotatedQuarter(turned);
      if (rot > 0) turned = shape;
      if (shape.mask.width > resolution || shape.mask.height > resolution) continue;
      Bitmap m = coarsen(shape.mask, block);
      bool placed = false;
      for (int y = 0; y + m.height <= grid && !placed && y + m.height < bestTop; ++y)
        for (int x = 0; x + m.width <= grid; ++x)
          if (fits(atlas, m, x, y)) {
            placements[c] = {rot, x * block, y * block};
            bestTop = y + m.height;
            shapes[c] = std::move(shape);
            bestMask = std::move(m);
            placed = true;
            break;
          }
    }
    if (bestTop == (1 << 30)) return false;
    stamp(atlas, bestMask, placements[c].x / block, placements[c].y / block);
  }
  size_t taken = 0;
  for (uint64_t w : atlas.bits) taken += __builtin_popcountll(w);
  used = static_cast<double>(taken) / (static_cast<double>(grid) * grid);
  return true;
}

// One packing tried at a density.
struct Packing {
  double density = 0;
  bool fits = false;
  double used = 0;
  std::vector<Placement> placements;
  std::vector<ChartShape> shapes;
};

struct DensitySearch {
  Packing packing;   // the densest that fits
  int attempts = 0;  // packings the search needed (those tried ahead and not needed are not counted)
};

// The densest packing that fits: from the area bound down by 7% steps, then up again by bisection of the
// densities' ratio. With several parts (common/thread_team.h) each round packs, side by side, the density the
// search tries next and those it would try after it if that one failed (going down) or fit (bisecting): the
// same sequence of densities as one part tries one by one, so the same atlas, in fewer rounds
// (armadillo-sub2: 5 instead of 8).
DensitySearch densestPacking(const std::vector<Chart>& charts, int resolution, int gutter) {
  const int block = std::max(1, resolution / kPackGrid);
  const int parts = ThreadTeam::usefulParts();
  const auto packAll = [&](std::vector<Packing>& tries) {
    runParts(std::min<int>(parts, static_cast<int>(tries.size())), [&](int part) {
      for (size_t i = part; i < tries.size(); i += parts) {
        Packing& t = tries[i];
        t.fits = pack(charts, t.density, resolution, gutter, block, t.placements, t.shapes, t.used);
      }
    });
  };
  double surfaceArea = 0;
  for (const Chart& c : charts) surfaceArea += c.surfaceArea;
  double fail = resolution / std::sqrt(surfaceArea);  // 100% of the square: never fits with gutters
  double density = 0.85 * fail;
  DensitySearch out;
  while (!out.packing.fits) {
    std::vector<Packing> tries(parts);
    for (int k = 0; k < parts; ++k) tries[k].density = density * std::pow(0.93, k);
    packAll(tries);
    for (Packing& t : tries) {
      ++out.attempts;
      if (t.fits) {
        out.packing = std::move(t);
        break;
      }
      fail = t.density;
      density = 0.93 * t.density;
    }
    if (!out.packing.fits && density < 1e-12 * fail)
      throw InputError("atlas: the charts do not fit the resolution");
  }
  for (int it = 0; it < kBisections && fail / out.packing.density > kDensityPrecision;) {
    // The next density, and those after it should each fit.
    std::vector<Packing> tries;
    for (double ok = out.packing.density; static_cast<int>(tries.size()) < parts &&
                                          it + tries.size() < kBisections && fail / ok > kDensityPrecision;) {
      tries.emplace_back().density = std::sqrt(ok * fail);
      ok = tries.back().density;
    }
    packAll(tries);
    for (Packing& t : tries) {
      ++out.attempts, ++it;
      if (!t.fits) {
        fail = t.density;
        break;  // those after it assumed it fit
      }
      out.packing = std::move(t);
    }
  }
  return out;
}

void checkInput(const SurfaceMesh& mesh) {
  if (mesh.numFaces() == 0) throw InputError("atlas: the mesh has no faces");
  if (mesh.positions.size() % 3 || mesh.triangles.size() % 3)
    throw InputError("atlas: positions and triangles must come in threes");
  const int32_t nV = mesh.numVertices();
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    if (mesh.triangles[i] < 0 || mesh.triangles[i] >= nV)
      throw InputError("atlas: face " + std::to_string(i / 3) + " refers to vertex " +
                       std::to_string(mesh.triangles[i]) + " (the mesh has " + std::to_string(nV) + ")");
  for (double p : mesh.positions)
    if (!std::isfinite(p)) throw InputError("atlas: the mesh has a non-finite vertex coordinate");
}

// Length of the edges between two charts over the length of all edges (each edge counted once).
double seamShare(const FaceGeometry& g, const std::vector<int32_t>& faceChart) {
  const int32_t nF = g.topology.numFaces;
  if (faceChart.size() != static_cast<size_t>(nF)) return 0;
  double seam = 0, total = 0;
  for (int32_t f = 0; f < nF; ++f)
    for (int k = 0; k < 3; ++k) {
      const int32_t o = neighbour(g.topology, f, k);
      if (o >= 0 && o < f) continue;  // the other side counts it
      const double l = cornerEdgeLength(g, f, k);
      total += l;
      if (o >= 0 && faceChart[o] != faceChart[f]) seam += l;
    }
  return total > 0 ? seam / total : 0;
}

void checkOptions(int resolution, int gutterTexels) {
  if (resolution < 16 || resolution > 8192)
    throw InputError("atlas: resolution must be in [16, 8192] (got " + std::to_string(resolution) + ")");
  if (gutterTexels < 0 || gutterTexels > 16)
    throw InputError("atlas: gutter must be in [0, 16] texels (got " + std::to_string(gutterTexels) + ")");
}

}  // namespace

std::vector<uint16_t> rasterCoverage(const std::vector<float>& cornerUVs, int n) {
  std::vector<uint16_t> count(static_cast<size_t>(n) * n, 0);
  // Edge function of p against a -> b, ties broken by the top-left rule so shared edges count once.
  auto inside = [](double ax, double ay, double bx, double by, double px, double py) {
    const double e = (bx - ax) * (py - ay) - (by - ay) * (px - ax);
    if (e != 0) return e > 0;
    const double dy = by - ay, dx = bx - ax;
    return dy < 0 || (dy == 0 && dx > 0);
  };
  for (size_t f = 0; f + 6 <= cornerUVs.size(); f += 6) {
    double ax = cornerUVs[f] * n, ay = cornerUVs[f + 1] * n, bx = cornerUVs[f + 2] * n,
           by = cornerUVs[f + 3] * n, cx = cornerUVs[f + 4] * n, cy = cornerUVs[f + 5] * n;
    const double area = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
    if (!(std::abs(area) > 1e-12)) continue;
    if (area < 0) std::swap(bx, cx), std::swap(by, cy);
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({ax, bx, cx}) - 0.5)));
    const int x1 = std::min(n - 1, static_cast<int>(std::ceil(std::max({ax, bx, cx}) - 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({ay, by, cy}) - 0.5)));
    const int y1 = std::min(n - 1, static_cast<int>(std::ceil(std::max({ay, by, cy}) - 0.5)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        if (inside(ax, ay, bx, by, px, py) && inside(bx, by, cx, cy, px, py) &&
            inside(cx, cy, ax, ay, px, py)) {
          uint16_t& c = count[static_cast<size_t>(y) * n + x];
          if (c < 65535) ++c;
        }
      }
  }
  return count;
}

namespace {

AtlasMeasures measure(const SurfaceMesh& mesh, const FaceGeometry& g, const std::vector<float>& cornerUVs,
                      const std::vector<int32_t>& faceChart, int resolution) {
  AtlasMeasures m;
  m.resolution = resolution;
  const std::vector<uint16_t> count = rasterCoverage(cornerUVs, resolution);
  size_t covered = 0, twice = 0;
  for (uint16_t c : count) covered += c > 0, twice += c > 1;
  m.coverage = static_cast<double>(covered) / count.size();
  m.overlap = covered ? static_cast<double>(twice) / covered : 0;
  const int32_t nF = mesh.numFaces();
  // Majority orientation per chart (or over everything).
  std::vector<double> orientation;
  std::vector<double> uvArea(nF);
  for (int32_t f = 0; f < nF; ++f) {
    double t[6];
    for (int k = 0; k < 6; ++k) t[k] = static_cast<double>(cornerUVs[6 * f + k]) * resolution;
    uvArea[f] = signedArea2(t) / 2;
    const size_t c = faceChart.empty() ? 0 : static_cast<size_t>(std::max(0, faceChart[f]));
    if (orientation.size() <= c) orientation.resize(c + 1, 0);
    orientation[c] += uvArea[f];
  }
  std::vector<std::pair<double, double>> density;
  for (int32_t f = 0; f < nF; ++f)
    if (g.areas[f] > 0) density.push_back({std::sqrt(std::abs(uvArea[f]) / g.areas[f]), g.areas[f]});
  const auto [p05, median, p95] =
      weightedQuantiles(std::move(density), std::array<double, 3>{0.05, 0.5, 0.95});
  m.texelsPerUnitLength = median;
  if (!(median > 0)) return m;
  m.densityP05 = p05 / median;
  m.densityP95 = p95 / median;
  m.densityMin = 1e300, m.densityMax = 0;
  double stretch2 = 0, area = 0;
  for (int32_t f = 0; f < nF; ++f) {
    if (!(g.areas[f] > 0)) continue;
    const double d = std::sqrt(std::abs(uvArea[f]) / g.areas[f]) / median;
    if (d < 1e-3) {
      ++m.degenerateFaces;
      continue;
    }
    const size_t c = faceChart.empty() ? 0 : static_cast<size_t>(std::max(0, faceChart[f]));
    if (uvArea[f] * orientation[c] < 0) ++m.flippedFaces;
    m.densityMin = std::min(m.densityMin, d), m.densityMax = std::max(m.densityMax, d);
    // Sander's L2 stretch of the texture-to-surface map, texel lengths over the median density.
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    double s[6];
    for (int k = 0; k < 6; ++k) s[k] = static_cast<double>(cornerUVs[6 * f + k]) * resolution / median;
    const double A2 = signedArea2(s);
    const Eigen::Vector3d Ss = (p[0] * (s[3] - s[5]) + p[1] * (s[5] - s[1]) + p[2] * (s[1] - s[3])) / A2;
    const Eigen::Vector3d St = (p[0] * (s[4] - s[2]) + p[1] * (s[0] - s[4]) + p[2] * (s[2] - s[0])) / A2;
    stretch2 += g.areas[f] * (Ss.squaredNorm() + St.squaredNorm()) / 2;
    area += g.areas[f];
  }
  m.stretchL2 = area > 0 ? std::sqrt(stretch2 / area) : 0;
  m.seamShare = seamShare(g, faceChart);
  if (m.densityMax == 0) m.densityMin = 0;
  return m;
}

}  // namespace

AtlasMeasures measureAtlas(const SurfaceMesh& mesh, const MeshTopology& topology,
                           const std::vector<float>& cornerUVs, const std::vector<int32_t>& faceChart,
                           int resolution) {
  return measure(mesh, faceGeometry(mesh, topology), cornerUVs, faceChart, resolution);
}

TextureAtlas generateAtlas(const SurfaceMesh& mesh, int resolution, int gutterTexels) {
  checkOptions(resolution, gutterTexels);
  checkInput(mesh);
  return generateAtlas(mesh, buildTopology(mesh), resolution, gutterTexels);
}

TextureAtlas generateAtlas(const SurfaceMesh& mesh, const MeshTopology& topology, int resolution,
                           int gutterTexels) {
  const auto t0 = std::chrono::steady_clock::now();
  checkOptions(resolution, gutterTexels);
  checkInput(mesh);
  const FaceGeometry g = faceGeometry(mesh, topology);
  TextureAtlas atlas;
  atlas.resolution = resolution;
  atlas.gutter = gutterTexels;
  const std::vector<Chart> charts = makeCharts(mesh, g, atlas.splits, atlas.keptPieces);
  atlas.chartMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (charts.empty()) throw InputError("atlas: every face of the mesh has zero area");
  atlas.numCharts = static_cast<int>(charts.size());

  const DensitySearch found = densestPacking(charts, resolution, gutterTexels);
  atlas.packAttempts = found.attempts;
  atlas.used = found.packing.used;
  const std::vector<Placement>& best = found.packing.placements;
  const std::vector<ChartShape>& bestShapes = found.packing.shapes;

  const int32_t nF = mesh.numFaces();
  atlas.cornerUVs.assign(6 * static_cast<size_t>(nF), 0.0f);
  atlas.faceChart.assign(nF, -1);
  for (size_t c = 0; c < charts.size(); ++c) {
    const ChartShape& s = bestShapes[c];
    for (size_t j = 0; j < charts[c].faces.size(); ++j) {
      const int32_t f = charts[c].faces[j];
      atlas.faceChart[f] = static_cast<int32_t>(c);
      for (int k = 0; k < 3; ++k) {
        atlas.cornerUVs[6 * f + 2 * k] =
            static_cast<float>((s.texel[6 * j + 2 * k] + best[c].x) / resolution);
        atlas.cornerUVs[6 * f + 2 * k + 1] =
            static_cast<float>((s.texel[6 * j + 2 * k + 1] + best[c].y) / resolution);
      }
    }
  }
  atlas.measures = measure(mesh, g, atlas.cornerUVs, atlas.faceChart, resolution);
  atlas.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return atlas;
}

AtlasCheck checkAtlasUVs(const std::vector<float>& cornerUVs, int32_t numFaces, int resolution) {
  AtlasCheck out;
  if (numFaces <= 0 || cornerUVs.size() != 6 * static_cast<size_t>(numFaces)) {
    out.reason = "the model has no TEXCOORD_0";
    return out;
  }
  constexpr double eps = 1e-4;
  for (int32_t f = 0; f < numFaces; ++f) {
    const float* u = &cornerUVs[6 * static_cast<size_t>(f)];
    if (!std::all_of(u, u + 6, [](float x) { return std::isfinite(x); })) {
      ++out.nonFinite;
      continue;
    }
    if (std::any_of(u, u + 6, [](float x) { return x < -eps || x > 1 + eps; })) ++out.outside;
    double t[6];
    for (int k = 0; k < 6; ++k) t[k] = u[k];
    if (!(std::abs(signedArea2(t) / 2) * resolution * resolution > 1e-6)) ++out.degenerate;
  }
  if (out.nonFinite) {
    out.reason = std::to_string(out.nonFinite) + " faces have non-finite UVs";
    return out;
  }
  if (out.outside) {
    out.reason =
        std::to_string(out.outside) + " faces have UVs outside [0, 1] (a tiling layout, not an atlas)";
    return out;
  }
  if (out.degenerate > 0.01 * numFaces) {
    out.reason = std::to_string(out.degenerate) + " faces have (near-)zero UV area";
    return out;
  }
  const std::vector<uint16_t> count = rasterCoverage(cornerUVs, resolution);
  size_t covered = 0, twice = 0;
  for (uint16_t c : count) covered += c > 0, twice += c > 1;
  out.coverage = static_cast<double>(covered) / count.size();
  out.overlap = covered ? static_cast<double>(twice) / covered : 0;
  if (!covered) {
    out.reason = "the UV triangles cover no texel";
    return out;
  }
  if (twice > 0.005 * covered) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", 100.0 * out.overlap);
    out.reason = std::string("UV triangles overlap on ") + buf + "% of the covered texels";
    return out;
  }
  out.usable = true;
  out.reason = "TEXCOORD_0 is a valid non-overlapping atlas";
  return out;
}

}  // namespace tvf
