#include "dec/exterior_derivative.h"

#include <algorithm>
#include <vector>

namespace tvf {

namespace {

// The triplet builds, for a topology whose edges have more than two faces (a non-manifold mesh the checks
// refuse, but whose operators a test may still ask for).
SparseMatrix d1FromTriplets(const MeshTopology& t) {
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(3 * t.numFaces);
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int32_t c = 0; c < 3; ++c) entries.emplace_back(f, t.edgeOf(f, c), t.signOf(f, c));
  SparseMatrix d1(t.numFaces, t.numEdges);
  d1.setFromTriplets(entries.begin(), entries.end());
  return d1;
}

}  // namespace

// Built in place, column by column, from what the topology already holds in order (each vertex's edges and
// each edge's faces, ascending): no triplets to sort (armadillo-sub2's 1.25M edges: the operators took a
// quarter of a second of its opening in wasm).
SparseMatrix exteriorDerivative0(const MeshTopology& t) {
  SparseMatrix d0(t.numEdges, t.numVertices);
  d0.resizeNonZeros(2 * static_cast<Eigen::Index>(t.numEdges));
  std::copy(t.vertexEdgeStart.begin(), t.vertexEdgeStart.end(), d0.outerIndexPtr());
  for (int32_t v = 0; v < t.numVertices; ++v)
    for (int32_t k = t.vertexEdgeStart[v]; k < t.vertexEdgeStart[v + 1]; ++k) {
      const int32_t e = t.vertexEdgeList[k];
      d0.innerIndexPtr()[k] = e;
      d0.valuePtr()[k] = t.edgeVertices[2 * e] == v ? -1.0 : 1.0;
    }
  return d0;
}

SparseMatrix exteriorDerivative1(const MeshTopology& t) {
  for (int32_t e = 0; e < t.numEdges; ++e)
    if (t.edgeFaceCount[e] > 2 || (t.edgeFaceCount[e] == 2 && t.edgeFaces[2 * e] == t.edgeFaces[2 * e + 1]))
      return d1FromTriplets(t);
  SparseMatrix d1(t.numFaces, t.numEdges);
  Eigen::Index count = 0;
  for (int32_t e = 0; e < t.numEdges; ++e) count += t.edgeFaceCount[e];
  d1.resizeNonZeros(count);
  int* outer = d1.outerIndexPtr();
  outer[0] = 0;
  for (int32_t e = 0, next = 0; e < t.numEdges; ++e) {
    for (int k = 0; k < t.edgeFaceCount[e]; ++k) {
      const int32_t f = t.edgeFaces[2 * e + k];
      int32_t c = 0;
      while (t.edgeOf(f, c) != e) ++c;
      d1.innerIndexPtr()[next] = f;
      d1.valuePtr()[next] = t.signOf(f, c);
      ++next;
    }
    outer[e + 1] = next;
  }
  return d1;
}

}  // namespace tvf
