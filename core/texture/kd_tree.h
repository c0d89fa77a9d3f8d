#pragma once
// A k-d tree over float points of a small fixed dimension (the 8-dimensional appearance / neighbourhood vectors),
// for the k-coherence search: exact k-nearest-neighbour queries with a per-point exclusion predicate.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace tvf {

class KdTree {
 public:
  // `points`: n rows of `dims` floats, row-major; the tree keeps a pointer, so they must outlive it.
  KdTree(const float* points, int n, int dims, int leafSize = 8);

  // The `count` nearest points to `query` (squared Euclidean distance) among those for which skip(index) is false,
  // nearest first, as (distance^2, index). Fewer when fewer points qualify. With maxChecks > 0 the search is
  // approximate: once that many points were examined, no further subtree is opened (the nearest-first descent
  // has usually found the true neighbours by then).
  template <typename Skip>
  void nearest(const float* query, int count, Skip&& skip, std::vector<std::pair<float, int32_t>>& out,
               int maxChecks = 0) const;

  int size() const { return n_; }
  int dims() const { return dims_; }

 private:
  struct Node {
    int32_t begin, end;   // range in order_
    int32_t left = -1, right = -1;
    int32_t dim = -1;     // -1 for a leaf
    float split = 0;
  };
  int32_t build(int32_t begin, int32_t end, int leafSize);
  template <typename Skip>
  void search(int32_t node, const float* query, int count, Skip& skip, std::vector<std::pair<float, int32_t>>& heap,
              int& budget) const;

  const float* points_;
  int n_, dims_;
  std::vector<int32_t> order_;
  std::vector<Node> nodes_;
};

// ---------------------------------------------------------------------------------------------- implementation
template <typename Skip>
void KdTree::nearest(const float* query, int count, Skip&& skip, std::vector<std::pair<float, int32_t>>& out,
                     int maxChecks) const {
  out.clear();
  if (count <= 0 || nodes_.empty()) return;
  int budget = maxChecks > 0 ? maxChecks : n_ + 1;
  search(0, query, count, skip, out, budget);  // `out` is a max-heap on distance while searching
  std::sort_heap(out.begin(), out.end());
}

template <typename Skip>
void KdTree::search(int32_t index, const float* query, int count, Skip& skip,
                    std::vector<std::pair<float, int32_t>>& heap, int& budget) const {
  const Node& node = nodes_[index];
  if (node.dim < 0) {
    budget -= node.end - node.begin;
    for (int32_t k = node.begin; k < node.end; ++k) {
      const int32_t p = order_[k];
      const float* x = points_ + static_cast<size_t>(p) * dims_;
      float d = 0;
      for (int c = 0; c < dims_; ++c) d += (x[c] - query[c]) * (x[c] - query[c]);
      if (static_cast<int>(heap.size()) == count && d >= heap.front().first) continue;
      if (skip(p)) continue;
      if (static_cast<int>(heap.size()) == count) {
        std::pop_heap(heap.begin(), heap.end());
        heap.back() = {d, p};
      } else {
        heap.emplace_back(d, p);
      }
      std::push_heap(heap.begin(), heap.end());
    }
    return;
  }
  const float diff = query[node.dim] - node.split;
  const int32_t nearChild = diff < 0 ? node.left : node.right;
  const int32_t farChild = diff < 0 ? node.right : node.left;
  search(nearChild, query, count, skip, heap, budget);
  if (static_cast<int>(heap.size()) < count || (budget > 0 && diff * diff < heap.front().first))
    search(farChild, query, count, skip, heap, budget);
}

}  // namespace tvf
