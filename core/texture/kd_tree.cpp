#include "texture/kd_tree.h"

#include <algorithm>
#include <numeric>

namespace tvf {

KdTree::KdTree(const float* points, int n, int dims, int leafSize) : points_(points), n_(n), dims_(dims) {
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  if (n > 0) {
    nodes_.reserve(2 * static_cast<size_t>(n / std::max(1, leafSize)) + 2);
    build(0, n, std::max(1, leafSize));
  }
}

int32_t KdTree::build(int32_t begin, int32_t end, int leafSize) {
  const int32_t index = static_cast<int32_t>(nodes_.size());
  nodes_.push_back({begin, end});
  if (end - begin <= leafSize) return index;
  // Split the dimension of largest spread at its median.
  int bestDim = 0;
  float bestSpread = -1;
  for (int c = 0; c < dims_; ++c) {
    float lo = points_[static_cast<size_t>(order_[begin]) * dims_ + c], hi = lo;
    for (int32_t k = begin + 1; k < end; ++k) {
      const float v = points_[static_cast<size_t>(order_[k]) * dims_ + c];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (hi - lo > bestSpread) bestSpread = hi - lo, bestDim = c;
  }
  if (bestSpread <= 0) return index;  // all points equal: keep them in one leaf
  const int32_t mid = begin + (end - begin) / 2;
  const auto value = [&](int32_t p) { return points_[static_cast<size_t>(p) * dims_ + bestDim]; };
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](int32_t a, int32_t b) { return value(a) < value(b); });
  const float split = value(order_[mid]);
  nodes_[index].dim = bestDim;
  nodes_[index].split = split;
  const int32_t left = build(begin, mid, leafSize);
  const int32_t right = build(mid, end, leafSize);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

}  // namespace tvf
