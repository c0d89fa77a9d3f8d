#include "direction/trivial_connection.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/angles.h"
#include "common/input_error.h"

namespace tvf {
namespace {

double principal(double angle, int symmetry) {
  const double period = kTwoPi / symmetry;
  return angle - period * std::round(angle / period);
}

// Each closed component's prescribed index sum.
std::vector<double> componentSums(const MeshTopology& t, const std::map<int32_t, double>& prescribed) {
  std::vector<double> sums(t.components.size(), 0.0);
  for (const auto& [v, index] : prescribed) sums[t.vertexComponent[v]] += index;
  return sums;
}

}  // namespace

bool indicesComplete(const MeshTopology& t, const std::map<int32_t, double>& prescribed) {
  const std::vector<double> sums = componentSums(t, prescribed);
  for (size_t c = 0; c < t.components.size(); ++c)
    if (t.components[c].boundaryLoops == 0 && std::abs(sums[c] - t.components[c].eulerCharacteristic) > 1e-9)
      return false;
  return true;
}

std::vector<double> holonomyTargets(const MeshTopology& t, const MeshGeometry& g,
                                    const std::map<int32_t, double>& indices) {
  std::vector<double> b(t.numVertices, 0.0);
  for (int32_t v = 0; v < t.numVertices; ++v)
    if (!t.isBoundaryVertex[v] && t.vertexFaceCount[v] > 0) b[v] = -g.angleDefect[v];
  for (const auto& [v, index] : indices) b[v] += kTwoPi * index;
  return b;
}

TrivialConnection::TrivialConnection(const MeshTopology& topology, const FaceConnection& connection)
    : topology_(topology),
      connection_(connection),
      cycles_(dualCycles(topology, connection)),
      factor_(std::vector<uint8_t>(cycles_.vertexRows, 0)) {
  double mean = 0;
  for (const double w : connection.weight) mean += w;
  mean = connection.weight.empty() ? 1.0 : mean / static_cast<double>(connection.weight.size());
  inverseWeight_.resize(connection.weight.size());
  for (size_t k = 0; k < connection.weight.size(); ++k)
    inverseWeight_[k] = 1.0 / std::max(connection.weight[k], 1e-12 * mean);
}

void TrivialConnection::factorVertexBlock() {
  const DualCycles& d = cycles_;
  const int32_t entries = static_cast<int32_t>(inverseWeight_.size());
  std::vector<Eigen::Triplet<double, int>> triplets;
  for (int32_t k = 0; k < entries; ++k) {
    const int32_t h = d.vertexRow[d.entryHigh[k]], l = d.vertexRow[d.entryLow[k]];
    if (h >= 0) triplets.emplace_back(h, h, inverseWeight_[k]);
    if (l >= 0) triplets.emplace_back(l, l, inverseWeight_[k]);
    if (h >= 0 && l >= 0) triplets.emplace_back(std::min(h, l), std::max(h, l), -inverseWeight_[k]);
  }
  for (int32_t r = 0; r < d.vertexRows; ++r) triplets.emplace_back(r, r, 0.0);  // every diagonal stored
  vertexBlock_.resize(d.vertexRows, d.vertexRows);
  vertexBlock_.setFromTriplets(triplets.begin(), triplets.end());
  scale_ = 0;
  for (int32_t r = 0; r < d.vertexRows; ++r) scale_ += vertexBlock_.coeff(r, r);
  scale_ = d.vertexRows > 0 ? scale_ / d.vertexRows : 1.0;
  const DiagonalTerms none;
  if (d.vertexRows > 0) factor_.factor(vertexBlock_, scale_, none);

  // The generators' coupling to the vertex cycles and among themselves, and the Schur complement.
  const int32_t generators = static_cast<int32_t>(d.generators.size());
  std::vector<Eigen::Triplet<double, int>> coupling;
  Eigen::MatrixXd among = Eigen::MatrixXd::Zero(generators, generators);
  std::vector<double> column(entries, 0.0);
  for (int32_t j = 0; j < generators; ++j) {
    const DualCycle& cycle = d.generators[j];
    for (size_t i = 0; i < cycle.entries.size(); ++i) column[cycle.entries[i]] += cycle.signs[i];
    for (size_t i = 0; i < cycle.entries.size(); ++i) {
      const int32_t k = cycle.entries[i];
      const double value = cycle.signs[i] * inverseWeight_[k];
      const int32_t h = d.vertexRow[d.entryHigh[k]], l = d.vertexRow[d.entryLow[k]];
      if (h >= 0) coupling.emplace_back(h, j, d.highSign[k] * value);
      if (l >= 0) coupling.emplace_back(l, j, -d.highSign[k] * value);
    }
    for (int32_t i = 0; i < generators; ++i) {
      const DualCycle& other = d.generators[i];
      double sum = 0;
      for (size_t m = 0; m < other.entries.size(); ++m)
        sum += other.signs[m] * column[other.entries[m]] * inverseWeight_[other.entries[m]];
      among(i, j) = sum;
    }
    for (size_t i = 0; i < cycle.entries.size(); ++i) column[cycle.entries[i]] = 0;
  }
  coupling_.resize(d.vertexRows, generators);
  coupling_.setFromTriplets(coupling.begin(), coupling.end());
  solvedCoupling_.resize(d.vertexRows, generators);
  for (int32_t j = 0; j < generators; ++j) {
    Eigen::VectorXd z;
    const Eigen::VectorXd bj = Eigen::VectorXd(coupling_.col(j));
    factor_.solve(vertexBlock_, scale_, none, bj, z);
    solvedCoupling_.col(j) = z;
  }
  schur_ = among - Eigen::MatrixXd(coupling_.transpose()) * solvedCoupling_;
  factored_ = true;
}

std::vector<double> TrivialConnection::rotations(const std::vector<double>& vertexTargets, int symmetry) {
  const auto start = std::chrono::steady_clock::now();
  if (!factored_) factorVertexBlock();
  const DualCycles& d = cycles_;
  Eigen::VectorXd b(d.vertexRows);
  for (int32_t v = 0; v < topology_.numVertices; ++v)
    if (d.vertexRow[v] >= 0) b[d.vertexRow[v]] = vertexTargets[v];
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(d.vertexRows);
  if (d.vertexRows > 0) factor_.solve(vertexBlock_, scale_, DiagonalTerms{}, b, lambda);
  // What the vertex cycles alone leave each generator, rounded to the nearest multiple of 2 pi / N.
  const int32_t generators = static_cast<int32_t>(d.generators.size());
  Eigen::VectorXd lambdaG = Eigen::VectorXd::Zero(generators);
  if (generators > 0) {
    const Eigen::VectorXd sums = coupling_.transpose() * lambda;
    Eigen::VectorXd change(generators);
    for (int32_t j = 0; j < generators; ++j) {
      const DualCycle& cycle = d.generators[j];
      double holonomy = sums[j];
      for (size_t i = 0; i < cycle.entries.size(); ++i)
        holonomy += cycle.signs[i] * connection_.angle[cycle.entries[i]];
      change[j] = -principal(holonomy, symmetry);
    }
    lambdaG = schur_.ldlt().solve(change);
    lambda -= solvedCoupling_ * lambdaG;
  }
  std::vector<double> x(inverseWeight_.size(), 0.0);
  for (size_t k = 0; k < x.size(); ++k) {
    const int32_t h = d.vertexRow[d.entryHigh[k]], l = d.vertexRow[d.entryLow[k]];
    double sum = 0;
    if (h >= 0) sum += d.highSign[k] * lambda[h];
    if (l >= 0) sum -= d.highSign[k] * lambda[l];
    x[k] = sum;
  }
  for (int32_t j = 0; j < generators; ++j) {
    const DualCycle& cycle = d.generators[j];
    for (size_t i = 0; i < cycle.entries.size(); ++i) x[cycle.entries[i]] += cycle.signs[i] * lambdaG[j];
  }
  for (size_t k = 0; k < x.size(); ++k) x[k] *= inverseWeight_[k];
  solveMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return x;
}

std::vector<double> TrivialConnection::parallelAngles(const std::vector<double>& x) const {
  const FaceConnection& c = connection_;
  std::vector<double> theta(topology_.numFaces, 0.0);
  for (const int32_t g : cycles_.treeOrder) {
    const int32_t k = cycles_.parentEntry[g];
    if (k < 0) continue;
    const double turn = c.angle[k] + x[k];  // theta_F = theta_G + turn
    theta[g] = c.faceF[k] == g ? theta[c.faceG[k]] + turn : theta[c.faceF[k]] - turn;
  }
  return theta;
}

double TrivialConnection::parallelResidual(const std::vector<double>& x, const std::vector<double>& theta,
                                           int symmetry) const {
  const FaceConnection& c = connection_;
  double worst = 0;
  for (size_t k = 0; k < x.size(); ++k)
    worst = std::max(
        worst, std::abs(principal(theta[c.faceF[k]] - theta[c.faceG[k]] - c.angle[k] - x[k], symmetry)));
  return worst;
}

}  // namespace tvf
