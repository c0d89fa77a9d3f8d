#include "mesh/mesh_topology.h"

#include <algorithm>
#include <numeric>

#include "common/union_find.h"

namespace tvf {
namespace {

int32_t lowerOf(const SurfaceMesh& mesh, int32_t h) {
  return std::min(mesh.triangles[h], mesh.triangles[h - h % 3 + (h % 3 + 1) % 3]);
}

// The half-edges in canonical edge order: by lower vertex (a counting sort, which keeps corner order), then
// by upper vertex within each vertex's few. Equal (lower, upper) runs are one edge, their corners in corner
// order: what a sort of all 3F keys gives, in linear time (the sort was the largest part of opening a 1M-face
// scan).
std::vector<int32_t> halfEdgesByEdge(const SurfaceMesh& mesh, int32_t nV, std::vector<int32_t>& upper) {
  const std::vector<int32_t>& T = mesh.triangles;
  const size_t nH = T.size();
  std::vector<int32_t> start(static_cast<size_t>(nV) + 1, 0);
  upper.resize(nH);
  for (size_t h = 0; h < nH; ++h) {
    const int32_t a = T[h], b = T[h - h % 3 + (h % 3 + 1) % 3];
    upper[h] = std::max(a, b);
    ++start[std::min(a, b) + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int32_t> order(nH);
  std::vector<int32_t> fill(start.begin(), start.end() - 1);
  for (size_t h = 0; h < nH; ++h)
    order[fill[lowerOf(mesh, static_cast<int32_t>(h))]++] = static_cast<int32_t>(h);
  for (int32_t v = 0; v < nV; ++v)
    std::sort(order.begin() + start[v], order.begin() + start[v + 1],
              [&](int32_t g, int32_t h) { return upper[g] != upper[h] ? upper[g] < upper[h] : g < h; });
  return order;
}

void buildEdges(const SurfaceMesh& mesh, MeshTopology& t) {
  const int32_t nF = t.numFaces;
  std::vector<int32_t> upper;
  const std::vector<int32_t> order = halfEdgesByEdge(mesh, t.numVertices, upper);
  const auto sameEdge = [&](size_t k) {
    return k > 0 && upper[order[k]] == upper[order[k - 1]] &&
           lowerOf(mesh, order[k]) == lowerOf(mesh, order[k - 1]);
  };
  size_t numEdges = 0;
  for (size_t k = 0; k < order.size(); ++k) numEdges += sameEdge(k) ? 0 : 1;
  t.edgeVertices.reserve(2 * numEdges);
  t.edgeFaceCount.reserve(numEdges);
  t.edgeFaces.reserve(2 * numEdges);
  t.faceEdges.assign(3 * nF, -1);
  t.faceEdgeSigns.assign(3 * nF, 0);
  for (size_t k = 0; k < order.size(); ++k) {
    const int32_t corner = order[k], f = corner / 3, c = corner % 3;
    if (!sameEdge(k)) {
      t.edgeVertices.push_back(lowerOf(mesh, corner));
      t.edgeVertices.push_back(upper[corner]);
      t.edgeFaceCount.push_back(0);
      t.edgeFaces.push_back(-1);
      t.edgeFaces.push_back(-1);
    }
    const int32_t e = static_cast<int32_t>(t.edgeFaceCount.size()) - 1;
    t.faceEdges[corner] = e;
    t.faceEdgeSigns[corner] = mesh.triangles[3 * f + c] < mesh.triangles[3 * f + (c + 1) % 3] ? 1 : -1;
    if (t.edgeFaceCount[e] < 2) t.edgeFaces[2 * e + t.edgeFaceCount[e]] = f;
    ++t.edgeFaceCount[e];
  }
  t.numEdges = static_cast<int32_t>(t.edgeFaceCount.size());
}

void markBoundary(const SurfaceMesh& mesh, MeshTopology& t) {
  t.isBoundaryEdge.assign(t.numEdges, 0);
  t.isBoundaryVertex.assign(t.numVertices, 0);
  t.vertexFaceCount.assign(t.numVertices, 0);
  for (int32_t e = 0; e < t.numEdges; ++e) {
    if (t.edgeFaceCount[e] != 1) continue;
    t.isBoundaryEdge[e] = 1;
    t.isBoundaryVertex[t.edgeVertices[2 * e]] = 1;
    t.isBoundaryVertex[t.edgeVertices[2 * e + 1]] = 1;
  }
  for (const int32_t v : mesh.triangles) ++t.vertexFaceCount[v];
  t.vertexEdgeStart.assign(t.numVertices + 1, 0);
  for (const int32_t v : t.edgeVertices) ++t.vertexEdgeStart[v + 1];
  std::partial_sum(t.vertexEdgeStart.begin(), t.vertexEdgeStart.end(), t.vertexEdgeStart.begin());
  t.vertexEdgeList.resize(t.edgeVertices.size());
  std::vector<int32_t> fill(t.vertexEdgeStart.begin(), t.vertexEdgeStart.end() - 1);
  for (int32_t e = 0; e < t.numEdges; ++e) {
    t.vertexEdgeList[fill[t.edgeVertices[2 * e]]++] = e;
    t.vertexEdgeList[fill[t.edgeVertices[2 * e + 1]]++] = e;
  }
}

// Follows each boundary edge (in its face's direction) to the boundary edge leaving its head vertex.
void traceBoundaryLoops(const SurfaceMesh& mesh, MeshTopology& t) {
  std::vector<int32_t> outgoing(t.numVertices, -1), headOf(t.numEdges, -1);
  std::vector<int32_t> outgoingCount(t.numVertices, 0);
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int32_t c = 0; c < 3; ++c) {
      const int32_t e = t.edgeOf(f, c);
      if (!t.isBoundaryEdge[e]) continue;
      const int32_t tail = mesh.triangles[3 * f + c];
      outgoing[tail] = e;
      ++outgoingCount[tail];
      headOf[e] = mesh.triangles[3 * f + (c + 1) % 3];
    }
  std::vector<uint8_t> visited(t.numEdges, 0);
  for (int32_t start = 0; start < t.numEdges; ++start) {
    if (!t.isBoundaryEdge[start] || visited[start]) continue;
    std::vector<int32_t> loop;
    int32_t e = start;
    while (e >= 0 && !visited[e]) {
      visited[e] = 1;
      loop.push_back(e);
      const int32_t head = headOf[e];
      // A vertex with several outgoing boundary edges is non-manifold; the checks report it, we stop here.
      e = outgoingCount[head] == 1 ? outgoing[head] : -1;
    }
    t.boundaryLoops.push_back(std::move(loop));
  }
}

void labelComponents(const SurfaceMesh& mesh, MeshTopology& t) {
  UnionFind faces(t.numFaces);
  for (int32_t e = 0; e < t.numEdges; ++e)
    if (t.edgeFaces[2 * e + 1] >= 0) faces.unite(t.edgeFaces[2 * e], t.edgeFaces[2 * e + 1]);
  std::vector<int32_t> label(t.numFaces, -1);
  t.faceComponent.assign(t.numFaces, -1);
  int32_t count = 0;
  for (int32_t f = 0; f < t.numFaces; ++f) {
    const int32_t root = faces.find(f);
    if (label[root] < 0) label[root] = count++;
    t.faceComponent[f] = label[root];
  }
  t.components.assign(count, ComponentInfo{});
  t.vertexComponent.assign(t.numVertices, -1);
  for (int32_t f = 0; f < t.numFaces; ++f) {
    ++t.components[t.faceComponent[f]].faces;
    for (int32_t c = 0; c < 3; ++c) t.vertexComponent[mesh.triangles[3 * f + c]] = t.faceComponent[f];
  }
  for (int32_t v = 0; v < t.numVertices; ++v)
    if (t.vertexComponent[v] >= 0) ++t.components[t.vertexComponent[v]].vertices;
  t.edgeComponent.assign(t.numEdges, -1);
  for (int32_t e = 0; e < t.numEdges; ++e) {
    t.edgeComponent[e] = t.faceComponent[t.edgeFaces[2 * e]];
    ++t.components[t.edgeComponent[e]].edges;
  }
  for (const auto& loop : t.boundaryLoops) ++t.components[t.edgeComponent[loop.front()]].boundaryLoops;
  for (auto& c : t.components) {
    c.eulerCharacteristic = c.vertices - c.edges + c.faces;
    c.genus = (2 - c.eulerCharacteristic - c.boundaryLoops) / 2;
  }
}

}  // namespace

int32_t MeshTopology::eulerCharacteristic() const {
  int32_t chi = 0;
  for (const auto& c : components) chi += c.eulerCharacteristic;
  return chi;
}

MeshTopology buildTopology(const SurfaceMesh& mesh) {
  MeshTopology t;
  t.numVertices = mesh.numVertices();
  t.numFaces = mesh.numFaces();
  buildEdges(mesh, t);
  markBoundary(mesh, t);
  traceBoundaryLoops(mesh, t);
  labelComponents(mesh, t);
  return t;
}

int32_t findEdge(const MeshTopology& t, int32_t a, int32_t b) {
  if (a < 0 || b < 0 || a >= t.numVertices || b >= t.numVertices) return -1;
  const int32_t lo = std::min(a, b), hi = std::max(a, b);
  for (int32_t k = t.vertexEdgeStart[lo]; k < t.vertexEdgeStart[lo + 1]; ++k) {
    const int32_t e = t.vertexEdgeList[k];
    if (t.edgeVertices[2 * e + 1] == hi) return e;
  }
  return -1;
}

}  // namespace tvf
