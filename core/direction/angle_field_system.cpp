#include "direction/angle_field_system.h"

#include <cmath>

#include "common/angles.h"

namespace tvf {
namespace {

constexpr int kMaxBranchSolves = 6;

SparseMatrix faceLaplacian(const MeshTopology& t, const FaceConnection& c) {
  std::vector<Eigen::Triplet<double, int>> triplets;
  for (size_t k = 0; k < c.faceF.size(); ++k) {
    const int32_t f = c.faceF[k], g = c.faceG[k];
    const double w = c.weight[k];
    triplets.emplace_back(f, f, w);
    triplets.emplace_back(g, g, w);
    triplets.emplace_back(f, g, -w);
    triplets.emplace_back(g, f, -w);
  }
  for (int32_t f = 0; f < t.numFaces; ++f) triplets.emplace_back(f, f, 0.0);
  SparseMatrix L(t.numFaces, t.numFaces);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

}  // namespace

AngleFieldSystem::AngleFieldSystem(const MeshTopology& topology, const FaceConnection& connection,
                                   int symmetry)
    : topology_(topology),
      symmetry_(symmetry),
      laplacian_(faceLaplacian(topology, connection)),
      base_(upperTriangle(laplacian_)),
      parallel_(topology.numFaces, 0.0),
      phi_(Eigen::VectorXd::Zero(topology.numFaces)),
      factor_(std::vector<uint8_t>(topology.numFaces, 1)) {
  double sum = 0;
  for (int32_t f = 0; f < topology.numFaces; ++f) sum += laplacian_.coeff(f, f);
  scale_ = topology.numFaces > 0 && sum > 0 ? sum / topology.numFaces : 1.0;
}

DiagonalTerms AngleFieldSystem::termsOf(const std::vector<FaceDirectionTerm>& terms, double weight) const {
  DiagonalTerms out;
  for (const FaceDirectionTerm& term : terms) {
    out.rows.push_back(term.face);
    out.weights.push_back(weight * scale_);
  }
  return out;
}

DiagonalTerms AngleFieldSystem::allTerms() const {
  DiagonalTerms all;
  for (const auto& [id, entry] : entries_) {
    const DiagonalTerms terms = termsOf(entry.terms, entry.weight);
    all.rows.insert(all.rows.end(), terms.rows.begin(), terms.rows.end());
    all.weights.insert(all.weights.end(), terms.weights.begin(), terms.weights.end());
  }
  return all;
}

void AngleFieldSystem::setFixedTerms(std::vector<FaceDirectionTerm> terms, double weight) {
  fixed_ = std::move(terms);
  fixedWeight_ = weight;
  SparseMatrix made = upperTriangle(plusDiagonal(laplacian_, termsOf(fixed_, weight)));
  takeMatrix(base_, made);
  factor_.invalidate();
}

void AngleFieldSystem::add(int32_t id, std::vector<FaceDirectionTerm> terms, double weight) {
  Entry& entry = entries_[id] = Entry{std::move(terms), weight};
  factor_.update(termsOf(entry.terms, weight), scale_, false);
}

void AngleFieldSystem::remove(int32_t id) {
  const auto it = entries_.find(id);
  if (it == entries_.end()) return;
  factor_.update(termsOf(it->second.terms, it->second.weight), scale_, true);
  entries_.erase(it);
}

void AngleFieldSystem::setWeight(int32_t id, double weight) {
  const auto it = entries_.find(id);
  if (it == entries_.end()) return;
  const double change = weight - it->second.weight;
  it->second.weight = weight;
  if (change != 0) factor_.update(termsOf(it->second.terms, std::abs(change)), scale_, change < 0);
}

void AngleFieldSystem::clear() {
  factor_.update(allTerms(), scale_, true);
  entries_.clear();
}

void AngleFieldSystem::setParallel(std::vector<double> parallelAngles) {
  parallel_ = std::move(parallelAngles);
}

void AngleFieldSystem::factorNow() {
  factor_.factor(base_, scale_, allTerms());
}

void AngleFieldSystem::targets(const std::vector<FaceDirectionTerm>& terms, bool unwrap,
                               std::vector<double>& out) const {
  const double period = kTwoPi / symmetry_;
  auto nearest = [&](double value, double to) { return value - period * std::round((value - to) / period); };
  const size_t first = out.size();
  double shift = 0;  // the group's mean distance to phi, to move it as a whole
  for (size_t i = 0; i < terms.size(); ++i) {
    const int32_t f = terms[i].face;
    const double wanted = std::arg(terms[i].power) / symmetry_ - parallel_[f];
    const double anchor = unwrap && i > 0 ? out.back() : phi_[f];
    out.push_back(nearest(wanted, anchor));
    shift += phi_[f] - out.back();
  }
  if (!unwrap || terms.empty()) return;
  const double whole = period * std::round(shift / static_cast<double>(terms.size()) / period);
  for (size_t i = first; i < out.size(); ++i) out[i] += whole;
}

Eigen::VectorXd AngleFieldSystem::rightHandSide(std::vector<double>& branches) const {
  branches.clear();
  targets(fixed_, false, branches);
  for (const auto& [id, entry] : entries_) targets(entry.terms, true, branches);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(topology_.numFaces);
  size_t i = 0;
  for (const FaceDirectionTerm& term : fixed_) b[term.face] += fixedWeight_ * scale_ * branches[i++];
  for (const auto& [id, entry] : entries_)
    for (const FaceDirectionTerm& term : entry.terms) b[term.face] += entry.weight * scale_ * branches[i++];
  return b;
}

void AngleFieldSystem::solve(std::vector<double>& theta) {
  iterations_ = 0;
  phi_.setZero();  // branches chosen from the design alone: a replayed design gets the same field
  if (!entries_.empty() || !fixed_.empty()) {
    const DiagonalTerms terms = allTerms();
    if (!factor_.current()) factor_.factor(base_, scale_, terms);
    std::vector<double> branches, previous;
    for (; iterations_ < kMaxBranchSolves; ++iterations_) {
      const Eigen::VectorXd b = rightHandSide(branches);
      if (iterations_ > 0 && branches == previous) break;
      Eigen::VectorXd phi;
      factor_.solve(base_, scale_, terms, b, phi);
      phi_ = std::move(phi);
      previous = branches;
    }
  }
  theta.resize(topology_.numFaces);
  for (int32_t f = 0; f < topology_.numFaces; ++f) theta[f] = parallel_[f] + phi_[f];
}

void AngleFieldSystem::assemble(SparseMatrix& A, Eigen::VectorXd& b) {
  A = plusDiagonal(fullFromUpper(base_), allTerms());
  std::vector<double> branches;
  b = rightHandSide(branches);
}

double AngleFieldSystem::nonZerosPerRow() const {
  const double nonZeros = 2.0 * static_cast<double>(base_.nonZeros()) - static_cast<double>(base_.rows());
  return nonZeros / std::max<Eigen::Index>(1, base_.rows());
}

}  // namespace tvf
