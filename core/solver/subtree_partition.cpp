#include "solver/subtree_partition.h"

#include <algorithm>
#include <functional>
#include <queue>
#include <utility>

namespace tvf {
namespace {

struct Forest {
  std::vector<int> childStart, children;  // children of s: children[childStart[s] .. childStart[s + 1])
  std::vector<int64_t> subtreeWork;
  std::vector<int> roots;
};

Forest forestOf(const std::vector<int>& parent, const std::vector<int64_t>& work) {
  const int n = static_cast<int>(parent.size());
  Forest f;
  f.childStart.assign(n + 1, 0);
  for (const int p : parent)
    if (p >= 0) ++f.childStart[p + 1];
  for (int s = 0; s < n; ++s) f.childStart[s + 1] += f.childStart[s];
  f.children.resize(f.childStart[n]);
  std::vector<int> fill(f.childStart.begin(), f.childStart.end() - 1);
  f.subtreeWork = work;
  for (int s = 0; s < n; ++s) {
    if (parent[s] < 0) {
      f.roots.push_back(s);
      continue;
    }
    f.children[fill[parent[s]]++] = s;
    f.subtreeWork[parent[s]] += f.subtreeWork[s];  // children come before their parent
  }
  return f;
}

// Longest-processing-time-first assignment of subtrees to `parts` groups: their loads, and each subtree's
// group in `owner` (same order as `subtrees`).
int64_t largestLoad(const Forest& f, const std::vector<int>& subtrees, int parts, std::vector<int>* owner) {
  std::vector<int> order(subtrees.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return f.subtreeWork[subtrees[a]] > f.subtreeWork[subtrees[b]]; });
  using Load = std::pair<int64_t, int>;
  std::priority_queue<Load, std::vector<Load>, std::greater<Load>> loads;
  for (int g = 0; g < parts; ++g) loads.push({0, g});
  if (owner) owner->assign(subtrees.size(), 0);
  int64_t largest = 0;
  for (const int k : order) {
    Load least = loads.top();
    loads.pop();
    least.first += f.subtreeWork[subtrees[k]];
    largest = std::max(largest, least.first);
    if (owner) (*owner)[k] = least.second;
    loads.push(least);
  }
  return largest;
}

// Everything in the top, on the calling thread: nothing worth splitting.
SubtreePartition oneThread(int n, int64_t totalWork) {
  SubtreePartition out;
  for (int s = n - 1; s >= 0; --s) out.top.push_back(s);
  out.topWork = out.totalWork = totalWork;
  return out;
}

void collectSubtree(const Forest& f, int root, std::vector<int>& into) {
  std::vector<int> stack{root};
  while (!stack.empty()) {
    const int s = stack.back();
    stack.pop_back();
    into.push_back(s);
    for (int c = f.childStart[s]; c < f.childStart[s + 1]; ++c) stack.push_back(f.children[c]);
  }
}

}  // namespace

SubtreePartition partitionSubtrees(const std::vector<int>& parent, const std::vector<int64_t>& work,
                                   int parts) {
  const int n = static_cast<int>(parent.size());
  int64_t totalWork = 0;
  for (const int64_t w : work) totalWork += w;
  if (n == 0 || parts < 2) return oneThread(n, totalWork);
  const Forest f = forestOf(parent, work);

  // Split the largest subtree below the cut, one at a time, and remember the cut that was best so far.
  const auto heavier = [&](int a, int b) { return f.subtreeWork[a] < f.subtreeWork[b]; };
  std::vector<int> frontier = f.roots, top;
  std::make_heap(frontier.begin(), frontier.end(), heavier);
  int64_t topWork = 0, best = totalWork;
  size_t bestTopSize = 0;
  // Past a few subtrees per part the groups are as even as they get; further splits only grow the top.
  const size_t enough = 32 * static_cast<size_t>(parts);
  while (!frontier.empty() && frontier.size() <= enough && topWork < best) {
    const int64_t span = topWork + largestLoad(f, frontier, parts, nullptr);
    if (span < best) {
      best = span;
      bestTopSize = top.size();
    }
    std::pop_heap(frontier.begin(), frontier.end(), heavier);
    const int s = frontier.back();
    frontier.pop_back();
    top.push_back(s);
    topWork += work[s];
    for (int c = f.childStart[s]; c < f.childStart[s + 1]; ++c) {
      frontier.push_back(f.children[c]);
      std::push_heap(frontier.begin(), frontier.end(), heavier);
    }
  }
  if (10 * best > 9 * totalWork) return oneThread(n, totalWork);

  // Replay the best cut: its top, and the subtrees hanging below it.
  top.resize(bestTopSize);
  std::vector<char> inTop(n, 0);
  for (const int s : top) inTop[s] = 1;
  std::vector<int> below;
  for (const int r : f.roots)
    if (!inTop[r]) below.push_back(r);
  for (const int s : top)
    for (int c = f.childStart[s]; c < f.childStart[s + 1]; ++c)
      if (!inTop[f.children[c]]) below.push_back(f.children[c]);
  SubtreePartition out;
  out.totalWork = totalWork;
  std::vector<int> owner;
  out.largestGroupWork = largestLoad(f, below, parts, &owner);
  out.groups.assign(parts, {});
  for (size_t k = 0; k < below.size(); ++k) collectSubtree(f, below[k], out.groups[owner[k]]);
  out.groups.erase(std::remove_if(out.groups.begin(), out.groups.end(),
                                  [](const std::vector<int>& g) { return g.empty(); }),
                   out.groups.end());
  for (std::vector<int>& g : out.groups) std::sort(g.rbegin(), g.rend());
  out.top = std::move(top);
  std::sort(out.top.rbegin(), out.top.rend());
  for (const int s : out.top) out.topWork += work[s];
  return out;
}

}  // namespace tvf
