// SPDX-License-Identifier: GPL-2.0-or-later
// SpdFactor with a symbolic factor made before: a graph's analysis, expanded to whole blocks, factors the
// block-expanded matrix without an analysis of its own (a stripe pattern's energy from its spacing's).
#include "solver/spd_solve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/sparse_matrix.h"
#include "solver/kept_symbolic.h"

namespace tvf {
namespace {

// The upper triangle of a grid graph's Laplacian plus the identity (SPD): n x n nodes, each joined to its
// right, lower and lower-right neighbours.
SparseMatrix gridMatrix(int n) {
  std::vector<Eigen::Triplet<double>> entries;
  const auto id = [n](int r, int c) { return r * n + c; };
  std::vector<double> degree(static_cast<size_t>(n) * n, 0.0);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      for (const auto& [dr, dc] : {std::pair{0, 1}, std::pair{1, 0}, std::pair{1, 1}}) {
        if (r + dr >= n || c + dc >= n) continue;
        const int a = id(r, c), b = id(r + dr, c + dc);
        entries.emplace_back(std::min(a, b), std::max(a, b), -1.0);
        degree[a] += 1, degree[b] += 1;
      }
  for (int i = 0; i < n * n; ++i) entries.emplace_back(i, i, degree[i] + 1.0);
  SparseMatrix out(n * n, n * n);
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

// kron(A, B) for B = [[2, 0.5], [0.5, 1]]: SPD, with A's graph in whole 2 x 2 blocks (upper triangle kept).
SparseMatrix blockExpanded(const SparseMatrix& upper) {
  const double b[2][2] = {{2.0, 0.5}, {0.5, 1.0}};
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < upper.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(upper, j); it; ++it)
      for (int p = 0; p < 2; ++p)
        for (int q = 0; q < 2; ++q) {
          const int row = 2 * static_cast<int>(it.row()) + p, col = 2 * j + q;
          if (row <= col) entries.emplace_back(row, col, it.value() * b[p][q]);
        }
  SparseMatrix out(2 * upper.rows(), 2 * upper.cols());
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

TEST(SpdFactor, ABlockExpandedMatrixTakesItsGraphsAnalysisExpanded) {
  const SparseMatrix graph = gridMatrix(24);
  SpdFactor nodes(graph, minimumDegree(graph));
  ASSERT_TRUE(nodes.ok());
  const KeptSymbolic symbolic = nodes.symbolic();
  const std::vector<int> permutation = nodes.permutation();
  ASSERT_FALSE(symbolic.empty());
  ASSERT_EQ(permutation.size(), static_cast<size_t>(graph.rows()));

  const SparseMatrix blocks = blockExpanded(graph);
  std::vector<int> expandedPermutation;
  for (const int v : permutation) expandedPermutation.insert(expandedPermutation.end(), {2 * v, 2 * v + 1});
  const KeptSymbolic expanded = expandedSymbolic(symbolic, 2);
  SpdFactor taken(blocks, expandedPermutation, expanded);
  SpdFactor analysed(blocks, expandedPermutation);
  ASSERT_TRUE(taken.ok());
  ASSERT_TRUE(analysed.ok());
  // Taken, not analysed again: its supernodes are the graph's, doubled, where an analysis of its own merges
  // them otherwise.
  EXPECT_EQ(taken.symbolic().super, expanded.super);
  EXPECT_EQ(taken.symbolic().s, expanded.s);
  EXPECT_NE(analysed.symbolic().super, expanded.super);

  Eigen::VectorXd b(blocks.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = std::sin(0.37 * static_cast<double>(i)) + 0.1;
  Eigen::VectorXd x, y;
  ASSERT_TRUE(taken.solve(b, x));
  ASSERT_TRUE(analysed.solve(b, y));
  const SparseMatrix full = fullFromUpper(blocks);
  EXPECT_LT((full * x - b).norm(), 1e-12 * b.norm());
  EXPECT_LT((x - y).norm(), 1e-12 * y.norm());
}

TEST(SpdFactor, ASymbolicFactorThatDoesNotFitIsRefusedAndTheMatrixAnalysed) {
  const SparseMatrix graph = gridMatrix(16);
  SpdFactor nodes(graph, minimumDegree(graph));
  ASSERT_TRUE(nodes.ok());
  std::vector<int> expandedPermutation;
  for (const int v : nodes.permutation())
    expandedPermutation.insert(expandedPermutation.end(), {2 * v, 2 * v + 1});
  // Of the right size but another graph's: the nodes alone, no edge (an identity's analysis), expanded.
  SparseMatrix identity(graph.rows(), graph.cols());
  identity.setIdentity();
  SpdFactor lone(identity, nodes.permutation());
  ASSERT_TRUE(lone.ok());
  const KeptSymbolic wrong = expandedSymbolic(lone.symbolic(), 2);
  ASSERT_FALSE(wrong.empty());

  const SparseMatrix blocks = blockExpanded(graph);
  SpdFactor refused(blocks, expandedPermutation, wrong);
  ASSERT_TRUE(refused.ok());
  EXPECT_NE(refused.symbolic().s, wrong.s);
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(blocks.rows(), -1.0, 2.0), x;
  ASSERT_TRUE(refused.solve(b, x));
  EXPECT_LT((fullFromUpper(blocks) * x - b).norm(), 1e-12 * b.norm());
}

}  // namespace
}  // namespace tvf
