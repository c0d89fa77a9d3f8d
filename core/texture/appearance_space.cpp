#include "texture/appearance_space.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "mesh/surface_mesh.h"

namespace tvf {

std::vector<int32_t> covarianceSubset(int size, int every) {
  std::vector<int32_t> out;
  if (every <= 1) return out;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      if ((x + y) % every == 0) out.push_back(y * size + x);
  return out;
}

PcaBasis pcaOfRows(const RowMatrixXf& samples, int dims, const std::vector<int32_t>& subset) {
  const Eigen::Index n = samples.rows(), D = samples.cols();
  if (n == 0 || D == 0) throw InputError("PCA of an empty sample set");
  if (dims < 1 || dims > D) throw InputError("PCA: kept dimensions must be in [1, input dimensions]");
  const Eigen::Index used = subset.empty() ? n : static_cast<Eigen::Index>(subset.size());
  const auto row = [&](Eigen::Index k) { return subset.empty() ? k : static_cast<Eigen::Index>(subset[k]); };
  for (int32_t r : subset)
    if (r < 0 || r >= n) throw InputError("PCA: subset row out of range");
  PcaBasis basis;
  // The mean in double (float sums over 10^5 rows lose digits the small eigenvalues need).
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(D);
  for (Eigen::Index k = 0; k < used; ++k) mean += samples.row(row(k)).transpose().cast<double>();
  mean /= static_cast<double>(used);
  basis.mean = mean.cast<float>();
  RowMatrixXf centred(used, D);
  for (Eigen::Index k = 0; k < used; ++k) centred.row(k) = samples.row(row(k)) - basis.mean.transpose();
  // The product runs in float (SIMD GEMM, also in wasm) as a symmetric rank update; the solver gets doubles.
  Eigen::MatrixXf cov = Eigen::MatrixXf::Zero(D, D);
  cov.selfadjointView<Eigen::Lower>().rankUpdate(centred.transpose());
  const Eigen::MatrixXd covd =
      cov.selfadjointView<Eigen::Lower>().toDenseMatrix().cast<double>() / static_cast<double>(used);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covd);
  if (solver.info() != Eigen::Success) throw InputError("PCA: eigen decomposition failed");
  // Eigen sorts ascending; we want descending.
  const Eigen::VectorXd values = solver.eigenvalues().reverse();
  const Eigen::MatrixXd vectors = solver.eigenvectors().rowwise().reverse();
  double total = 0, kept = 0;
  basis.eigenvalues.resize(D);
  for (Eigen::Index i = 0; i < D; ++i) {
    const double v = std::max(0.0, values[i]);
    basis.eigenvalues[i] = v;
    total += v;
    if (i < dims) kept += v;
  }
  basis.varianceKept = total > 0 ? kept / total : 1.0;
  basis.axes.resize(D, dims);
  for (int k = 0; k < dims; ++k) {
    Eigen::VectorXd axis = vectors.col(k);
    Eigen::Index arg = 0;
    axis.cwiseAbs().maxCoeff(&arg);
    if (axis[arg] < 0) axis = -axis;
    basis.axes.col(k) = axis.cast<float>();
  }
  return basis;
}

RowMatrixXf pcaProject(const PcaBasis& basis, const RowMatrixXf& samples) {
  RowMatrixXf out = samples * basis.axes;
  out.rowwise() -= (basis.axes.transpose() * basis.mean).transpose();
  return out;
}

RowMatrixXf colourNeighbourhoods(const ExemplarImage& level, int spacing, double tapSigma) {
  const int m = level.size;
  float weight[25];
  for (int j = -2; j <= 2; ++j)
    for (int i = -2; i <= 2; ++i)
      weight[(j + 2) * 5 + (i + 2)] =
          tapSigma > 0 ? static_cast<float>(std::exp(-(i * i + j * j) / (2 * tapSigma * tapSigma))) : 1.0f;
  RowMatrixXf out(static_cast<Eigen::Index>(m) * m, 75);
  for (int y = 0; y < m; ++y)
    for (int x = 0; x < m; ++x) {
      const Eigen::Index row = static_cast<Eigen::Index>(y) * m + x;
      for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
          const int t = (j + 2) * 5 + (i + 2);
          const float* p = level.at(x + i * spacing, y + j * spacing);
          for (int c = 0; c < 3; ++c) out(row, 3 * t + c) = weight[t] * p[c];
        }
    }
  return out;
}

AppearanceLevel appearanceLevel(const GaussianStack& stack, int level, const AppearanceOptions& options) {
  if (level < 0 || level >= stack.numLevels()) throw InputError("appearance space: no such stack level");
  AppearanceLevel out;
  out.level = level;
  out.spacing = GaussianStack::spacing(level);
  out.tapSpacing = std::max(1, out.spacing / 2);
  const RowMatrixXf raw = colourNeighbourhoods(stack.levels[level], out.tapSpacing, options.tapSigma);
  out.basis = pcaOfRows(raw, options.dims, covarianceSubset(stack.size(), options.covarianceSubsample));
  out.vectors = pcaProject(out.basis, raw);
  return out;
}

}  // namespace tvf
