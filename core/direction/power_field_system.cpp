#include "direction/power_field_system.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "common/input_error.h"
#include "direction/connection_laplacian.h"
#include "direction/principal_curvature.h"

namespace tvf {
namespace {

// Components with a handle or a boundary may carry a parallel N-field (a flat torus, a disc, a cylinder):
// their rows get the kernel shift; closed genus-0 components have none (their holonomy is never trivial).
std::vector<uint8_t> kernelRows(const MeshTopology& t) {
  std::vector<uint8_t> rows(2 * t.numFaces);
  for (int32_t f = 0; f < t.numFaces; ++f) {
    const ComponentInfo& c = t.components[t.faceComponent[f]];
    rows[2 * f] = rows[2 * f + 1] = c.genus > 0 || c.boundaryLoops > 0;
  }
  return rows;
}

double meanDiagonal(const SparseMatrix& A) {
  double sum = 0;
  for (int j = 0; j < A.outerSize(); ++j) sum += A.coeff(j, j);
  return A.rows() > 0 && sum > 0 ? sum / static_cast<double>(A.rows()) : 1.0;
}

// The smoothest field's Lanczos cycles stop when the Ritz residual is this small relative to the Ritz value,
// or after so many solves in all: near-degenerate lowest eigenvalues (a round sphere's) converge slowly, and
// then any field in their span is as smooth.
constexpr double kEigenTolerance = 1e-9;
constexpr int kLanczosSteps = 12;
constexpr int kMaxInverseIterations = 60;

}  // namespace

PowerFieldSystem::PowerFieldSystem(const SurfaceMesh& mesh, const MeshTopology& topology,
                                   const MeshGeometry& geometry, const FaceFrames& frames,
                                   const FaceConnection& connection, int symmetry)
    : mesh_(mesh),
      topology_(topology),
      geometry_(geometry),
      symmetry_(symmetry),
      frames_(frames),
      connection_(connectionLaplacian(connection, topology.numFaces, symmetry)),
      base_(upperTriangle(connection_)),
      mass_(powerFieldMass(geometry)),
      scale_(meanDiagonal(connection_)),
      factor_(kernelRows(topology)) {}

int PowerFieldSystem::symmetry() const {
  return symmetry_;
}
const FaceFrames& PowerFieldSystem::frames() const {
  return frames_;
}
ShiftedFactor& PowerFieldSystem::factor() {
  return factor_;
}

void PowerFieldSystem::setCurvatureAlignment(double s) {
  if (!std::isfinite(s) || s < 0) throw InputError("the curvature alignment must be a number >= 0");
  if (s > 0 && curvature_.empty())
    curvature_ = principalCurvaturePower(mesh_, topology_, geometry_, frames_, symmetry_);
  curvatureAlignment_ = s;
}

void PowerFieldSystem::setBoundaryTerms(std::vector<FaceDirectionTerm> terms, double weight) {
  boundaryTerms_ = std::move(terms);
  boundaryWeight_ = weight;
  const DiagonalTerms diagonal = termsOf(Entry{boundaryTerms_, weight}, weight);
  SparseMatrix made = upperTriangle(plusDiagonal(connection_, diagonal));
  takeMatrix(base_, made);
  factor_.invalidate();
}

DiagonalTerms PowerFieldSystem::termsOf(const Entry& entry, double weight) const {
  DiagonalTerms terms;
  for (const FaceDirectionTerm& term : entry.terms) {
    terms.rows.push_back(2 * term.face);
    terms.rows.push_back(2 * term.face + 1);
    terms.weights.push_back(weight * scale_);
    terms.weights.push_back(weight * scale_);
  }
  return terms;
}

DiagonalTerms PowerFieldSystem::allTerms() const {
  DiagonalTerms all;
  for (const auto& [id, entry] : entries_) {
    const DiagonalTerms terms = termsOf(entry, entry.weight);
    all.rows.insert(all.rows.end(), terms.rows.begin(), terms.rows.end());
    all.weights.insert(all.weights.end(), terms.weights.begin(), terms.weights.end());
  }
  return all;
}

void PowerFieldSystem::add(int32_t id, std::vector<FaceDirectionTerm> terms, double weight) {
  Entry& entry = entries_[id] = Entry{std::move(terms), weight};
  factor_.update(termsOf(entry, weight), scale_, false);
}

void PowerFieldSystem::remove(int32_t id) {
  const auto it = entries_.find(id);
  if (it == entries_.end()) return;
  factor_.update(termsOf(it->second, it->second.weight), scale_, true);
  entries_.erase(it);
}

void PowerFieldSystem::setWeight(int32_t id, double weight) {
  const auto it = entries_.find(id);
  if (it == entries_.end()) return;
  const double change = weight - it->second.weight;
  it->second.weight = weight;
  if (change != 0) factor_.update(termsOf(it->second, std::abs(change)), scale_, change < 0);
}

void PowerFieldSystem::clear() {
  factor_.update(allTerms(), scale_, true);  // one multi-column downdate: the base is unchanged
  entries_.clear();
}

double PowerFieldSystem::lastUpdateMs() const {
  return factor_.lastUpdateMs();
}

Eigen::VectorXd PowerFieldSystem::rightHandSide() {
  Eigen::VectorXd b = Eigen::VectorXd::Zero(base_.rows());
  if (curvatureAlignment_ > 0) {
    // Area relative to the mean face area, so s means the same on every mesh size.
    const double meanArea = geometry_.totalArea / std::max(1, topology_.numFaces);
    for (int32_t f = 0; f < topology_.numFaces; ++f) {
      const double w = curvatureAlignment_ * scale_ * geometry_.faceArea[f] / meanArea;
      b[2 * f] += w * curvature_[f].real();
      b[2 * f + 1] += w * curvature_[f].imag();
    }
  }
  for (const FaceDirectionTerm& term : boundaryTerms_) {
    b[2 * term.face] += boundaryWeight_ * scale_ * term.power.real();
    b[2 * term.face + 1] += boundaryWeight_ * scale_ * term.power.imag();
  }
  for (const auto& [id, entry] : entries_)
    for (const FaceDirectionTerm& term : entry.terms) {
      b[2 * term.face] += entry.weight * scale_ * term.power.real();
      b[2 * term.face + 1] += entry.weight * scale_ * term.power.imag();
    }
  return b;
}

void PowerFieldSystem::smoothestField(Eigen::VectorXd& u) {
  // A fixed pseudo-random start: the page and the CLI find the same field.
  Eigen::VectorXd x(base_.rows());
  uint64_t state = 0x9E3779B97F4A7C15ull;
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    x[k] = static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;
  }
  auto dotM = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return a.dot(mass_.cwiseProduct(b));
  };
  const DiagonalTerms none;
  report_.inverseIterations = 0;
  // Lanczos on A^-1 M (self-adjoint in the mass inner product), restarted from its best Ritz vector: the
  // largest eigenvalue of A^-1 M is the smoothest field's. Plain inverse iteration converges at the ratio of
  // the two lowest eigenvalues, ~0.8 per step on a bunny; a Krylov space of a dozen solves does far better.
  for (int cycle = 0; cycle < kMaxInverseIterations / kLanczosSteps; ++cycle) {
    std::vector<Eigen::VectorXd> V{x / std::sqrt(dotM(x, x))};
    std::vector<double> alpha, beta;
    for (int j = 0; j < kLanczosSteps; ++j) {
      Eigen::VectorXd w;
      factor_.solve(base_, scale_, none, mass_.cwiseProduct(V[j]), w);
      ++report_.inverseIterations;
      alpha.push_back(dotM(V[j], w));
      for (int pass = 0; pass < 2; ++pass)  // full reorthogonalisation, twice: V stays M-orthonormal
        for (const Eigen::VectorXd& v : V) w -= dotM(v, w) * v;
      const double b = std::sqrt(std::max(0.0, dotM(w, w)));
      beta.push_back(b);
      if (!(b > 1e-300)) break;
      V.push_back(w / b);
    }
    const int m = static_cast<int>(alpha.size());
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(m, m);
    for (int j = 0; j < m; ++j) {
      T(j, j) = alpha[j];
      if (j + 1 < m) T(j, j + 1) = T(j + 1, j) = beta[j];
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(T);
    const Eigen::VectorXd s = eig.eigenvectors().col(m - 1);
    const double theta = eig.eigenvalues()[m - 1];
    x.setZero();
    for (int j = 0; j < m; ++j) x += s[j] * V[j];
    x /= std::sqrt(dotM(x, x));
    // |beta_m s_m| is the Ritz pair's residual ||A^-1 M x - theta x||_M.
    if (std::abs(beta[m - 1] * s[m - 1]) < kEigenTolerance * theta) break;
  }
  report_.eigenvalue = x.dot(base_.selfadjointView<Eigen::Upper>() * x) / dotM(x, x);
  u = std::move(x);
}

void PowerFieldSystem::factorNow() {
  factor_.factor(base_, scale_, allTerms());
}

void PowerFieldSystem::solve(Eigen::VectorXd& u) {
  const DiagonalTerms terms = allTerms();
  if (!factor_.current()) factor_.factor(base_, scale_, terms);
  if (entries_.empty() && curvatureAlignment_ == 0 && boundaryTerms_.empty()) return smoothestField(u);
  report_ = {};
  factor_.solve(base_, scale_, terms, rightHandSide(), u);
}

SparseMatrix PowerFieldSystem::baseMatrix() const {
  return fullFromUpper(base_);
}

double PowerFieldSystem::scale() const {
  return scale_;
}

double PowerFieldSystem::nonZerosPerRow() const {
  const double nonZeros = 2.0 * static_cast<double>(base_.nonZeros()) - static_cast<double>(base_.rows());
  return nonZeros / std::max<Eigen::Index>(1, base_.rows());
}

const PowerFieldReport& PowerFieldSystem::report() const {
  return report_;
}

void PowerFieldSystem::assemble(SparseMatrix& A, Eigen::VectorXd& b) {
  A = plusDiagonal(fullFromUpper(base_), allTerms());
  b = rightHandSide();
}

}  // namespace tvf
