// SPDX-License-Identifier: GPL-2.0-or-later
#include "direction/stripe_region.h"

#include "common/sparse_matrix.h"
#include "solver/spd_solve.h"

namespace tvf {

StripeRegion grownRegion(const MeshTopology& t, const std::vector<int32_t>& triangles,
                         const std::vector<uint8_t>& changed, int rings) {
  std::vector<int32_t> hops(changed.size(), -1), queue;
  for (size_t v = 0; v < changed.size(); ++v)
    if (changed[v]) hops[v] = 0, queue.push_back(static_cast<int32_t>(v));
  for (size_t head = 0; head < queue.size(); ++head) {
    const int32_t v = queue[head];
    if (hops[v] >= rings) continue;
    for (int32_t k = t.vertexEdgeStart[v]; k < t.vertexEdgeStart[v + 1]; ++k) {
      const int32_t e = t.vertexEdgeList[k];
      const int32_t u = t.edgeVertices[2 * e] == v ? t.edgeVertices[2 * e + 1] : t.edgeVertices[2 * e];
      if (hops[u] < 0) hops[u] = hops[v] + 1, queue.push_back(u);
    }
  }
  StripeRegion out;
  out.local.assign(changed.size(), -1);
  for (size_t v = 0; v < changed.size(); ++v)
    if (hops[v] >= 0) out.local[v] = out.size++, out.vertices.push_back(static_cast<int32_t>(v));
  std::vector<uint8_t> edgeReached(static_cast<size_t>(t.numEdges), 0);
  for (int32_t face = 0; face < t.numFaces; ++face)
    if (faceReaches(out, &triangles[3 * static_cast<size_t>(face)])) {
      out.faces.push_back(face);
      for (int c = 0; c < 3; ++c) edgeReached[t.edgeOf(face, c)] = 1;
    }
  for (int32_t e = 0; e < t.numEdges; ++e)
    if (edgeReached[e]) out.edges.push_back(e);
  return out;
}

bool solveOnRegion(const std::vector<Eigen::Triplet<double>>& upper, const Eigen::VectorXd& b,
                   const StripeRegion& region, int per, Eigen::VectorXd& x, std::vector<int> ordering) {
  const Eigen::Index n = static_cast<Eigen::Index>(region.size) * per;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  if (b.size() == x.size())
    for (int32_t a = 0; a < region.size; ++a)
      rhs.segment(a * per, per) = b.segment(static_cast<Eigen::Index>(region.vertices[a]) * per, per);
  const auto localOf = [&](Eigen::Index i) -> Eigen::Index {
    const int32_t v = region.local[i / per];
    return v < 0 ? -1 : static_cast<Eigen::Index>(v) * per + i % per;
  };
  std::vector<Eigen::Triplet<double>> inner;
  inner.reserve(upper.size());
  for (const auto& e : upper) {
    const Eigen::Index li = localOf(e.row()), lj = localOf(e.col());
    if (li >= 0 && lj >= 0)
      inner.emplace_back(std::min(li, lj), std::max(li, lj), e.value());
    else if (li >= 0)
      rhs[li] -= e.value() * x[e.col()];
    else if (lj >= 0)
      rhs[lj] -= e.value() * x[e.row()];
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(inner.begin(), inner.end());
  SpdFactor factor(a, std::move(ordering));
  Eigen::VectorXd y;
  if (!factor.solve(rhs, y)) return false;
  for (int32_t a = 0; a < region.size; ++a)
    x.segment(static_cast<Eigen::Index>(region.vertices[a]) * per, per) = y.segment(a * per, per);
  return true;
}

namespace {

// The region's vertex graph: its vertices (local indices) and the edges between them, upper triangle.
SparseMatrix regionGraph(const MeshTopology& t, const StripeRegion& region) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(4 * static_cast<size_t>(region.size));
  for (int32_t a = 0; a < region.size; ++a) {
    const int32_t v = region.vertices[a];
    entries.emplace_back(a, a, 1.0);
    for (int32_t k = t.vertexEdgeStart[v]; k < t.vertexEdgeStart[v + 1]; ++k) {
      const int32_t e = t.vertexEdgeList[k];
      const int32_t u = t.edgeVertices[2 * e] == v ? t.edgeVertices[2 * e + 1] : t.edgeVertices[2 * e];
      if (const int32_t b = region.local[u]; b > a) entries.emplace_back(a, b, 1.0);
    }
  }
  SparseMatrix graph(region.size, region.size);
  graph.setFromTriplets(entries.begin(), entries.end());
  return graph;
}

}  // namespace

std::vector<int> regionOrdering(const MeshTopology& t, const StripeRegion& region,
                                const std::vector<int>& vertexOrdering) {
  if (vertexOrdering.empty())
    return region.size > 0 ? minimumDegree(regionGraph(t, region)) : std::vector<int>();
  std::vector<int> out;
  out.reserve(static_cast<size_t>(region.size));
  for (const int v : vertexOrdering)
    if (region.local[v] >= 0) out.push_back(region.local[v]);
  return out;
}

}  // namespace tvf
