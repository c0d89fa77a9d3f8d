#pragma once
// Parts of an elimination tree that a substitution can run at the same time.
//
// The backward substitution computes a column only after its ancestors; subtrees that are not nested do not
// read each other's columns. Cutting the tree below its top therefore leaves a top, done first and alone, and
// disjoint subtrees, which go to parts in groups of about equal work. The top is made of whole subtrees'
// roots: the largest subtree below the cut is split while that lowers top + the largest group (a nested
// dissection's separators are small and its halves even, so the top stays small; a minimum-degree ordering's
// tree often starts with a long chain that no cut parts).
#include <cstdint>
#include <vector>

namespace tvf {

struct SubtreePartition {
  std::vector<int> top;                  // nodes above the cut, in descending order
  std::vector<std::vector<int>> groups;  // each part's nodes, in descending order; empty: no parallel part
  int64_t topWork = 0, largestGroupWork = 0, totalWork = 0;
};

// parent[s] > s, or -1 at a root (a postordered forest, as the nodes of an elimination tree are numbered);
// work[s] > 0. Never more groups than parts, and none when splitting would not make the longest part at
// least a tenth shorter than the whole.
SubtreePartition partitionSubtrees(const std::vector<int>& parent, const std::vector<int64_t>& work,
                                   int parts);

}  // namespace tvf
