// SPDX-License-Identifier: GPL-2.0-or-later
#include "direction/stripe_region.h"

#include <algorithm>
#include <memory>

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

RegionSystem::RegionSystem(const MeshTopology& t, const StripeRegion& region, int per,
                           const Eigen::VectorXd& x)
    : region_(region),
      per_(per),
      held_(x),
      rhs_(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(region.size) * per)) {
  // Column (b, q) holds the rows of every unknown of b's neighbours before b in the region, then b's own up
  // to q: the upper triangle, rows ascending.
  const int32_t n = region.size * per;
  std::vector<int32_t> before;  // per region vertex b: its neighbours a < b, ascending, then b
  std::vector<int32_t> start(static_cast<size_t>(region.size) + 1, 0);
  for (int32_t b = 0; b < region.size; ++b) {
    const int32_t v = region.vertices[b];
    const size_t first = before.size();
    for (int32_t k = t.vertexEdgeStart[v]; k < t.vertexEdgeStart[v + 1]; ++k) {
      const int32_t e = t.vertexEdgeList[k];
      const int32_t u = t.edgeVertices[2 * e] == v ? t.edgeVertices[2 * e + 1] : t.edgeVertices[2 * e];
      if (const int32_t a = region.local[u]; a >= 0 && a < b) before.push_back(a);
    }
    std::sort(before.begin() + static_cast<ptrdiff_t>(first), before.end());
    before.push_back(b);
    start[b + 1] = static_cast<int32_t>(before.size());
  }
  size_t nnz = 0;
  for (int32_t b = 0; b < region.size; ++b)
    nnz += static_cast<size_t>(start[b + 1] - start[b] - 1) * per * per + per * (per + 1) / 2;
  upper_.resize(n, n);
  upper_.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer = upper_.outerIndexPtr();
  int* inner = upper_.innerIndexPtr();
  int32_t at = 0;
  for (int32_t b = 0; b < region.size; ++b)
    for (int q = 0; q < per; ++q) {
      outer[b * per + q] = at;
      for (int32_t k = start[b]; k < start[b + 1]; ++k) {
        const int32_t a = before[k];
        for (int p = 0; p < (a < b ? per : q + 1); ++p) inner[at++] = a * per + p;
      }
    }
  outer[n] = at;
  std::fill_n(upper_.valuePtr(), nnz, 0.0);
}

void RegionSystem::add(int32_t i, int32_t j, double value) {
  const int32_t li = localOf(i), lj = localOf(j);
  if (li >= 0 && lj >= 0) {
    const int32_t row = std::min(li, lj), col = std::max(li, lj);
    const int* first = upper_.innerIndexPtr() + upper_.outerIndexPtr()[col];
    const int* last = upper_.innerIndexPtr() + upper_.outerIndexPtr()[col + 1];
    const int* at = std::lower_bound(first, last, row);
    if (at == last || *at != row)
      missed_ = true;
    else
      upper_.valuePtr()[at - upper_.innerIndexPtr()] += value;
  } else if (li >= 0) {
    rhs_[li] -= value * held_[j];
  } else if (lj >= 0) {
    rhs_[lj] -= value * held_[i];
  }
}

void RegionSystem::addRhs(int32_t i, double value) {
  if (const int32_t li = localOf(i); li >= 0) rhs_[li] += value;
}

bool RegionSystem::solve(const std::vector<int>& vertexOrdering, Eigen::VectorXd& x,
                         const RegionAnalysis* given, RegionAnalysis* made) const {
  if (missed_) return false;
  const bool expand = given && given->per > 0 && per_ % given->per == 0 && !given->symbolic.empty();
  const int k = expand ? per_ / given->per : 1;
  const std::unique_ptr<SpdFactor> factor =
      expand ? std::make_unique<SpdFactor>(upper_, expandedOrdering(given->permutation, k),
                                           expandedSymbolic(given->symbolic, k))
             : std::make_unique<SpdFactor>(upper_, expandedOrdering(vertexOrdering, per_));
  if (made) *made = {factor->symbolic(), factor->permutation(), per_};
  Eigen::VectorXd y;
  if (!factor->solve(rhs_, y)) return false;
  for (int32_t a = 0; a < region_.size; ++a)
    x.segment(static_cast<Eigen::Index>(region_.vertices[a]) * per_, per_) = y.segment(a * per_, per_);
  return true;
}

std::vector<int> expandedOrdering(const std::vector<int>& vertices, int per) {
  std::vector<int> out;
  out.reserve(vertices.size() * per);
  for (const int v : vertices)
    for (int k = 0; k < per; ++k) out.push_back(per * v + k);
  return out;
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
