#include "quad/greedy_rounding.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "solver/spd_solve.h"

namespace tvf {
namespace {

enum class Kind : uint8_t { Continuous, Integer, Pinned };

// Solves the integers' dense system with those in `fixed` held at their values in x.
bool solveFree(const Eigen::MatrixXd& S, const Eigen::VectorXd& r, const std::vector<uint8_t>& fixed,
               Eigen::VectorXd& x) {
  std::vector<int32_t> free;
  for (int32_t i = 0; i < static_cast<int32_t>(fixed.size()); ++i)
    if (!fixed[i]) free.push_back(i);
  const int32_t n = static_cast<int32_t>(free.size());
  if (n == 0) return true;
  Eigen::MatrixXd A(n, n);
  Eigen::VectorXd rhs(n);
  for (int32_t a = 0; a < n; ++a) {
    rhs[a] = r[free[a]];
    for (int32_t j = 0; j < static_cast<int32_t>(fixed.size()); ++j)
      if (fixed[j]) rhs[a] -= S(free[a], j) * x[j];
    for (int32_t c = 0; c < n; ++c) A(a, c) = S(free[a], free[c]);
  }
  // A tiny ridge: an integer the energy does not see (S's row zero) stays where it is rather than failing.
  const double ridge = 1e-12 * std::max(1.0, A.diagonal().cwiseAbs().maxCoeff());
  A.diagonal().array() += ridge;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
  const Eigen::VectorXd y = ldlt.solve(rhs);
  if (!y.allFinite()) return false;
  for (int32_t a = 0; a < n; ++a) x[free[a]] = y[a];
  return true;
}

}  // namespace

GreedyRounding roundGreedily(const SparseMatrix& K, const Eigen::VectorXd& b,
                             const std::vector<uint8_t>& integer,
                             const std::vector<std::pair<int32_t, double>>& pinned,
                             const std::function<bool(double)>& progress) {
  GreedyRounding out;
  const int32_t n = static_cast<int32_t>(K.rows());
  out.z = Eigen::VectorXd::Zero(n);
  std::vector<Kind> kind(n, Kind::Continuous);
  std::vector<int32_t> index(n, -1);
  for (const auto& [i, value] : pinned) kind[i] = Kind::Pinned, out.z[i] = value;
  int32_t nc = 0, ni = 0;
  for (int32_t i = 0; i < n; ++i) {
    if (kind[i] == Kind::Pinned) continue;
    if (integer[i]) kind[i] = Kind::Integer;
    index[i] = kind[i] == Kind::Integer ? ni++ : nc++;
  }
  // The blocks, the pinned unknowns moved to the right-hand sides.
  std::vector<Eigen::Triplet<double>> cc, ci;
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(ni, ni);
  Eigen::VectorXd bc = Eigen::VectorXd::Zero(nc), bi = Eigen::VectorXd::Zero(ni);
  for (int32_t i = 0; i < n; ++i) {
    if (kind[i] == Kind::Continuous) bc[index[i]] += b[i];
    if (kind[i] == Kind::Integer) bi[index[i]] += b[i];
  }
  for (int32_t col = 0; col < K.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(K, col); it; ++it) {
      const int32_t row = static_cast<int32_t>(it.row());
      const Kind kr = kind[row], kc = kind[col];
      if (kr == Kind::Pinned) continue;
      Eigen::VectorXd& rhs = kr == Kind::Integer ? bi : bc;
      if (kc == Kind::Pinned) {
        rhs[index[row]] -= it.value() * out.z[col];
      } else if (kr == Kind::Continuous && kc == Kind::Continuous) {
        if (index[row] <= index[col]) cc.emplace_back(index[row], index[col], it.value());
      } else if (kr == Kind::Continuous && kc == Kind::Integer) {
        ci.emplace_back(index[row], index[col], it.value());
      } else if (kr == Kind::Integer && kc == Kind::Integer) {
        S(index[row], index[col]) += it.value();
      }
    }
  // A ridge far below the energy's scale: a chart placed by integers in one direction only (a cylinder
  // between two boundary iso-lines) is free to slide along the other, and takes the nearest place to 0 there.
  double diagonal = 0;
  for (const auto& c : cc)
    if (c.row() == c.col()) diagonal += std::abs(c.value());
  const double ridge = 1e-10 * diagonal / std::max<int32_t>(1, nc);
  for (int32_t i = 0; i < nc; ++i) cc.emplace_back(i, i, ridge);
  SparseMatrix Acc(nc, nc), Kci(nc, ni);
  Acc.setFromTriplets(cc.begin(), cc.end());
  Kci.setFromTriplets(ci.begin(), ci.end());
  cc.clear(), ci.clear();
  SpdFactor factor(Acc);
  if (!factor.ok()) return out;
  Eigen::VectorXd y0;
  if (!factor.solve(bc, y0)) return out;
  Eigen::VectorXd r = bi - Kci.transpose() * y0;
  constexpr int32_t kBlock = 16;
  for (int32_t c0 = 0; c0 < ni; c0 += kBlock) {
    const int32_t w = std::min(kBlock, ni - c0);
    Eigen::MatrixXd D = Eigen::MatrixXd(Kci.middleCols(c0, w)), Z;
    if (!factor.solve(D, Z)) return out;
    S.middleCols(c0, w) -= Kci.transpose() * Z;
    // The complement is most of the time on a big mesh (349 solves on armadillo-sub2): its share of the
    // progress is the first half.
    if (progress && !progress(0.5 * (c0 + w) / static_cast<double>(ni))) return out;
  }
  S = 0.5 * (S + S.transpose()).eval();

  Eigen::VectorXd x = Eigen::VectorXd::Zero(ni);
  std::vector<uint8_t> fixed(ni, 0);
  int32_t left = ni;
  for (;;) {
    if (!solveFree(S, r, fixed, x)) return out;
    if (progress && !progress(0.5 + 0.5 * (ni ? 1.0 - static_cast<double>(left) / ni : 1.0))) return out;
    if (left == 0) break;
    std::vector<std::pair<double, int32_t>> nearest;
    for (int32_t i = 0; i < ni; ++i)
      if (!fixed[i]) nearest.emplace_back(std::abs(x[i] - std::round(x[i])), i);
    const std::size_t batch = left <= 100 ? 1 : static_cast<std::size_t>(std::ceil(0.1 * left));
    std::partial_sort(nearest.begin(), nearest.begin() + batch, nearest.end());
    for (std::size_t k = 0; k < batch; ++k) {
      x[nearest[k].second] = std::round(x[nearest[k].second]);
      fixed[nearest[k].second] = 1;
    }
    left -= static_cast<int32_t>(batch);
    ++out.roundingSteps;
  }
  Eigen::VectorXd xc;
  if (!factor.solve(Eigen::VectorXd(bc - Kci * x), xc)) return out;
  for (int32_t i = 0; i < n; ++i) {
    if (kind[i] == Kind::Continuous) out.z[i] = xc[index[i]];
    if (kind[i] == Kind::Integer) out.z[i] = x[index[i]];
  }
  out.ok = true;
  return out;
}

}  // namespace tvf
