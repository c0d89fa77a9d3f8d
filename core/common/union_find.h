#pragma once
// Disjoint sets of 0..n-1 with path halving; the smaller index is each set's root. Components of a mesh
// (mesh/mesh_topology.cpp) and the primal tree of a tree-cotree decomposition (direction/dual_cycles.cpp).
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace tvf {

class UnionFind {
 public:
  explicit UnionFind(int32_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int32_t find(int32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  // Joins the sets of a and b; false when they were one set already.
  bool unite(int32_t a, int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<int32_t> parent_;
};

}  // namespace tvf
