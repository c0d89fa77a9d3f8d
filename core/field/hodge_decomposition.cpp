#include "field/hodge_decomposition.h"

#include <Eigen/SparseCholesky>
#include <chrono>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace tvf {
namespace {

// Both Poisson matrices are singular only by constants per connected component, and their right-hand sides
// are orthogonal to those. A relative shift of 1e-12 makes them definite; a few steps of iterative refinement
// against the unshifted matrix then remove the shift's bias (of relative size 1e-12 / the smallest nonzero
// eigenvalue, 1e-8 and more on fine meshes), and the kernel is projected out at the end.
Eigen::VectorXd solveSemidefinite(const SparseMatrix& A, const Eigen::VectorXd& b,
                                  const std::vector<int>& component, int components) {
  SparseMatrix shifted = A;
  const double shift = 1e-12 * meanDiagonal(A);
  for (int k = 0; k < shifted.rows(); ++k) shifted.coeffRef(k, k) += shift;
  Eigen::SimplicialLDLT<SparseMatrix> solver(shifted);
  if (solver.info() != Eigen::Success) throw std::runtime_error("Hodge decomposition: factorization failed");
  const auto removeKernel = [&](Eigen::VectorXd& x) {
    std::vector<double> sum(components, 0.0);
    std::vector<int> count(components, 0);
    for (int k = 0; k < x.size(); ++k)
      if (component[k] >= 0) sum[component[k]] += x[k], ++count[component[k]];
    for (int k = 0; k < x.size(); ++k)
      if (component[k] >= 0) x[k] -= sum[component[k]] / count[component[k]];
  };
  Eigen::VectorXd x = solver.solve(b);
  removeKernel(x);
  const double bNorm = b.norm();
  for (int step = 0; step < 4 && bNorm > 0; ++step) {
    const Eigen::VectorXd r = b - A * x;
    if (r.norm() <= 1e-15 * bNorm) break;
    x += solver.solve(r);
    removeKernel(x);
  }
  return x;
}

// Connected components of the graph whose edges are the rows (alongColumns = false) or columns of a sparse
// matrix with two nonzeros each; elements in no such row/column get -1 (they carry nothing).
int components(const SparseMatrix& M, bool alongColumns, std::vector<int>& label) {
  const int n = alongColumns ? M.rows() : M.cols();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<char> used(n, 0);
  const SparseMatrix T = alongColumns ? SparseMatrix(M) : SparseMatrix(M.transpose());
  for (int c = 0; c < T.outerSize(); ++c) {
    int first = -1;
    for (SparseMatrix::InnerIterator it(T, c); it; ++it) {
      used[it.row()] = 1;
      if (first < 0)
        first = it.row();
      else
        parent[find(it.row())] = find(first);
    }
  }
  label.assign(n, -1);
  std::vector<int> id(n, -1);
  int count = 0;
  for (int k = 0; k < n; ++k) {
    if (!used[k]) continue;
    const int root = find(k);
    if (id[root] < 0) id[root] = count++;
    label[k] = id[root];
  }
  return count;
}

}  // namespace

HodgeDecomposition hodgeDecompose(const SparseMatrix& d0, const SparseMatrix& d1, const MeshGeometry& g,
                                  const Eigen::VectorXd& c) {
  const auto start = std::chrono::steady_clock::now();
  HodgeDecomposition h;
  const bool starPositive = g.star1.size() > 0 && g.star1.minCoeff() > 0;
  h.metric = starPositive ? g.star1 : g.whitneyMass1;
  h.metricName = starPositive ? "star1" : "whitney-mass";
  const Eigen::VectorXd& P = h.metric;
  // Exact part: min |c - d a|_P  <=>  d0' P d0 a = d0' P c. Its kernel: constants per component (vertices
  // joined by edges).
  std::vector<int> vertexComponent, faceComponent;
  const int nv = components(d0, false, vertexComponent);
  const SparseMatrix L0 = d0.transpose() * P.asDiagonal() * d0;
  h.potential0 = solveSemidefinite(L0, d0.transpose() * P.asDiagonal() * c, vertexComponent, nv);
  h.exact = d0 * h.potential0;
  // Coexact part: delta b = P^-1 d1' b' with (d1 P^-1 d1') b' = d1 c (b' = *2 b). Its kernel: constants
  // per closed component (faces joined by interior edges; a boundary edge's column has one entry, which
  // makes the component's constant no kernel vector, so those are left out of the projection).
  const int nf = components(d1, true, faceComponent);
  std::vector<char> open(nf, 0);
  for (int e = 0; e < d1.outerSize(); ++e) {
    int n = 0, f = -1;
    for (SparseMatrix::InnerIterator it(d1, e); it; ++it) ++n, f = it.row();
    if (n == 1) open[faceComponent[f]] = 1;
  }
  for (int& label : faceComponent)
    if (label >= 0 && open[label]) label = -1;
  const Eigen::VectorXd Pinv = P.cwiseInverse();
  const SparseMatrix L2 = d1 * Pinv.asDiagonal() * d1.transpose();
  h.potential2 = solveSemidefinite(L2, d1 * c, faceComponent, nf);
  h.coexact = Pinv.asDiagonal() * (d1.transpose() * h.potential2);
  h.harmonic = c - h.exact - h.coexact;
  h.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return h;
}

HodgeEnergyShares hodgeEnergyShares(const HodgeDecomposition& h) {
  const auto energy = [&](const Eigen::VectorXd& x) { return x.dot(h.metric.asDiagonal() * x); };
  const double total = energy(h.exact + h.coexact + h.harmonic);
  HodgeEnergyShares s;
  if (!(total > 0)) return s;
  s.exact = energy(h.exact) / total;
  s.coexact = energy(h.coexact) / total;
  s.harmonic = energy(h.harmonic) / total;
  return s;
}

}  // namespace tvf
