#include "dec/exterior_derivative.h"

#include <vector>

namespace tvf {

SparseMatrix exteriorDerivative0(const MeshTopology& t) {
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(2 * t.numEdges);
  for (int32_t e = 0; e < t.numEdges; ++e) {
    entries.emplace_back(e, t.edgeVertices[2 * e], -1.0);
    entries.emplace_back(e, t.edgeVertices[2 * e + 1], 1.0);
  }
  SparseMatrix d0(t.numEdges, t.numVertices);
  d0.setFromTriplets(entries.begin(), entries.end());
  return d0;
}

SparseMatrix exteriorDerivative1(const MeshTopology& t) {
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(3 * t.numFaces);
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int32_t c = 0; c < 3; ++c) entries.emplace_back(f, t.edgeOf(f, c), t.signOf(f, c));
  SparseMatrix d1(t.numFaces, t.numEdges);
  d1.setFromTriplets(entries.begin(), entries.end());
  return d1;
}

}  // namespace tvf
