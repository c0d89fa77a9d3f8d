#include "design/one_form_system.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "common/input_error.h"
#include "common/stopwatch.h"
#include "constraints/edge_rows.h"
#include "field/whitney_reconstruction.h"
#include "mesh/feature_edges.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

// Closed genus-0 components have no kernel; every other component (handles, boundary loops, and the extra
// modes of free boundaries) gets the shift.
std::vector<uint8_t> kernelEdges(const MeshTopology& topology) {
  std::vector<uint8_t> out(topology.numEdges);
  for (int32_t e = 0; e < topology.numEdges; ++e) {
    const ComponentInfo& c = topology.components[topology.edgeComponent[e]];
    out[e] = c.genus > 0 || c.boundaryLoops > 0;
  }
  return out;
}

}  // namespace

OneFormSystem::OneFormSystem(const DesignMesh& mesh, ConstraintSet& constraints,
                             const FieldSettings& settings)
    : mesh_(mesh),
      constraints_(constraints),
      boundary_(settings.boundary),
      gamma_(settings.gamma),
      factor_(kernelEdges(mesh.topology()), settings.ordering) {
  factor_.setEdgeGraph(mesh.topology().edgeVertices, mesh.topology().numVertices);
  configureFactor(factor_, settings);
  setFeatures(settings.featureEdges);
}

int64_t OneFormSystem::unknowns() const {
  return mesh_.topology().numEdges;
}

void OneFormSystem::setBoundary(const BoundaryCondition& bc) {
  boundary_ = bc;
  baseStale_ = true;
  factor_.invalidate();
}

void OneFormSystem::setFeatures(const std::vector<int32_t>& edges) {
  featureEdges_.clear();
  featureValues_.clear();
  const MeshTopology& t = mesh_.topology();
  for (const FeatureCurve& curve : featureCurves(t, edges))
    for (size_t i = 0; i < curve.edges.size(); ++i) {
      const Eigen::Vector3d along = curve.signs[i] * edgeVector(mesh_.mesh(), t, curve.edges[i]).normalized();
      for (int side = 0; side < 2; ++side)
        for (const EdgeRow& row :
             vectorRows(mesh_.mesh(), t, t.edgeFaces[2 * curve.edges[i] + side], along)) {
          featureEdges_.push_back(row.edge);
          featureValues_.push_back(row.value);
        }
    }
  baseStale_ = true;
  factor_.invalidate();
}

Eigen::VectorXd OneFormSystem::rightHandSide() {
  Eigen::VectorXd b = constraints_.rightHandSide(ops_, scale_);
  for (size_t i = 0; i < featureEdges_.size(); ++i)
    b[featureEdges_[i]] += kBoundaryWeight * scale_ * featureValues_[i];
  return b;
}

void OneFormSystem::setGamma(double gamma) {
  gamma_ = gamma;
  baseStale_ = true;
  factor_.invalidate();
}

void OneFormSystem::resume() {
  factor_.invalidate();  // rows may have come and gone while it was not in use
}

// The operators and the base matrix go with the factor (a quarter of a GB at 1.25M edges): the next
// model's, of the same sizes when it is the same mesh opened again, are then made where they were.
void OneFormSystem::releaseMemory() {
  factor_.release();
  ops_ = OneFormOperators();
  releaseMatrix(base_);
  baseStale_ = true;
}

void OneFormSystem::rebuildBase() {
  const MeshTopology& topology = mesh_.topology();
  const MeshGeometry& geometry = mesh_.geometry();
  const std::vector<double> angles = boundaryEdgeAngles(topology, boundary_);
  ops_ = buildOneFormOperators(mesh_.mesh(), topology, geometry, angles);
  constraints_.operatorsChanged();
  releaseMatrix(base_);  // the old one goes before the new one is assembled
  SparseMatrix made =
      gamma_ > 0 ? biLaplacianUpper(oneFormLaplacian(ops_, geometry), geometry, gamma_ * geometry.totalArea)
                 : oneFormLaplacianUpper(ops_, geometry);
  takeMatrix(base_, made);
  scale_ = meanDiagonal(base_);
  if (ops_.boundaryRows.rows() > 0) {
    const SparseMatrix Zt = ops_.boundaryRows.transpose();
    SparseMatrix sum = base_ + upperTriangle((kBoundaryWeight * scale_) * (Zt * ops_.boundaryRows));
    sum.makeCompressed();
    takeMatrix(base_, sum);
  }
  for (const int32_t e : featureEdges_) base_.coeffRef(e, e) += kBoundaryWeight * scale_;
  const double nonZeros = 2.0 * static_cast<double>(base_.nonZeros()) - static_cast<double>(base_.rows());
  nnzPerRowM_ = nonZeros / std::max<Eigen::Index>(1, base_.rows());
  baseStale_ = false;
  factor_.invalidate();
}

void OneFormSystem::requireBase() {
  if (baseStale_) rebuildBase();
}

DiagonalTerms OneFormSystem::constraintTerms() const {
  DiagonalTerms terms;
  constraints_.allWeightedRows(scale_, terms.rows, terms.weights);
  return terms;
}

void OneFormSystem::updateRows(int32_t id, double weight, bool downdate, DesignStats& stats) {
  DiagonalTerms change;
  constraints_.weightedRows(id, weight, scale_, change.rows, change.weights);
  factor_.update(change, scale_, downdate);
  stats.updateMs = factor_.lastUpdateMs();
}

int32_t OneFormSystem::add(const ConstraintSpec& spec, DesignStats& stats) {
  const int32_t id = constraints_.add(spec);
  stats.rowsMs = constraints_.lastRowsMs();
  if (isEdgeKind(spec.kind)) updateRows(id, spec.weight, false, stats);
  return id;
}

void OneFormSystem::remove(const ConstraintSpec& spec, DesignStats& stats) {
  if (isEdgeKind(spec.kind)) updateRows(spec.id, spec.weight, true, stats);
}

void OneFormSystem::reweight(const ConstraintSpec& spec, double previousWeight, DesignStats& stats) {
  const double change = spec.weight - previousWeight;
  updateRows(spec.id, std::abs(change), change < 0, stats);
}

void OneFormSystem::clear(DesignStats& stats) {
  factor_.update(constraintTerms(), scale_, true);  // one multi-column downdate: the base is unchanged
  stats.updateMs = factor_.lastUpdateMs();
}

void OneFormSystem::factorNow(DesignStats& stats) {
  requireBase();
  factor_.factor(base_, scale_, constraintTerms());
  stats.nnzPerRowM = nnzPerRowM_;
}

void OneFormSystem::solve(FieldSolution& field, DesignStats& stats) {
  stats.inverseIterations = 0;
  stats.smoothestEigenvalue = 0;
  if (baseStale_ || !factor_.current()) factorNow(stats);
  auto start = Clock::now();
  const Eigen::VectorXd b = rightHandSide();
  stats.rhsMs = msSince(start);
  if (!b.allFinite()) throw InputError("the constraints give a right-hand side that is not finite");
  stats.warnings = constraints_.warnings(boundary_);
  start = Clock::now();
  Eigen::VectorXd x;
  factor_.solve(base_, scale_, constraintTerms(), b, x);
  stats.solveMs = msSince(start);
  reportFactor(factor_, unknowns(), stats);  // the solve refactors when an updated factor lost precision
  if (!x.allFinite())
    throw InputError(
        "the field is not finite (the system is too badly conditioned for these constraints); "
        "the previous field is kept");
  start = Clock::now();
  tvf::faceVectors(mesh_.faceVectorMap(), mesh_.topology(), x.data(), faceScratch_);
  for (const double v : faceScratch_)
    if (!std::isfinite(v))
      throw InputError(
          "the field's vectors are not finite (magnitudes beyond double range on this mesh); "
          "the previous field is kept");
  field.symmetry = 1;
  field.unknowns = std::move(x);
  field.oneForm.assign(field.unknowns.data(), field.unknowns.data() + field.unknowns.size());
  std::swap(field.faceVectors, faceScratch_);
  stats.reconstructMs = msSince(start);
}

void OneFormSystem::vertexVectors(const FieldSolution& field, std::vector<double>& out) const {
  // The spare face array (the previous field's, 3 doubles per face) holds the threads' partial sums.
  tvf::vertexVectors(mesh_.vertexVectorMap(), mesh_.faceVectorMap(), mesh_.mesh(), mesh_.topology(),
                     mesh_.geometry(), field.oneForm.data(), out, faceScratch_);
}

void OneFormSystem::assemble(SparseMatrix& A, Eigen::VectorXd& b) {
  requireBase();
  A = plusDiagonal(fullFromUpper(base_), constraintTerms());
  b = rightHandSide();
}

SparseMatrix OneFormSystem::baseMatrix() {
  requireBase();
  return fullFromUpper(base_);
}

double OneFormSystem::weightScale() {
  requireBase();
  return scale_;
}

}  // namespace tvf
