#include "design/designer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "constraints/constraint_set.h"
#include "dec/exterior_derivative.h"
#include "dec/one_form_laplacian.h"
#include "field/whitney_reconstruction.h"
#include "mesh/mesh_checks.h"
#include "solver/shifted_factor.h"

namespace tvf {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Fixed-angle boundary rows are enforced this strongly relative to the mean diagonal.
constexpr double kBoundaryWeight = 1e4;

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

struct Designer::Impl {
  SurfaceMesh mesh;
  MeshTopology topology;
  MeshGeometry geometry;
  BoundaryCondition boundary;
  double gamma = 0;

  // Base system, rebuilt when the boundary condition or gamma change.
  bool baseStale = true;
  OneFormOperators ops;
  SparseMatrix base;
  double scale = 1;

  ConstraintSet constraints;
  ShiftedFactor factor;

  Eigen::VectorXd solution;
  std::vector<double> oneForm, faceVectors, vertexVectors;
  std::vector<Singularity> singularities;
  // Derived on first read, each on its own: the page's default view needs the vertex vectors only.
  bool vertexVectorsStale = false, singularitiesStale = false;
  VertexVectorMap vertexVectorMap;  // built on first use (geometry only)
  FaceVectorMap faceVectorMap;      // likewise
  DesignStats stats;

  Impl(SurfaceMesh m, MeshTopology t)
      : mesh(std::move(m)),
        topology(std::move(t)),
        geometry(computeMeshGeometry(mesh, topology)),
        constraints(mesh, topology, geometry),
        factor(kernelEdges(topology)) {
    factor.setEdgeGraph(topology.edgeVertices, topology.numVertices);
    stats.positiveAreaFallbackVertices = geometry.positiveAreaFallbackVertices;
  }

  void rebuildBase() {
    const std::vector<double> angles = boundaryEdgeAngles(topology, boundary);
    ops = buildOneFormOperators(mesh, topology, geometry, angles);
    constraints.operatorsChanged();
    base = oneFormLaplacian(ops, geometry);
    if (gamma > 0) base = biLaplacian(base, geometry, gamma * geometry.totalArea);
    scale = meanDiagonal(base);
    if (ops.boundaryRows.rows() > 0) {
      const SparseMatrix Zt = ops.boundaryRows.transpose();
      base += (kBoundaryWeight * scale) * (Zt * ops.boundaryRows);
    }
    base.makeCompressed();
    stats.nnzPerRowM = static_cast<double>(base.nonZeros()) / std::max<Eigen::Index>(1, base.rows());
    baseStale = false;
    factor.invalidate();
  }

  DiagonalTerms constraintTerms() const {
    DiagonalTerms terms;
    constraints.allWeightedRows(scale, terms.rows, terms.weights);
    return terms;
  }

  // The factorization's figures; after every factorization, including the one a solve may redo.
  void copyFactorReport() {
    const FactorReport& r = factor.report();
    stats.analyzeMs = r.analyzeMs;
    stats.analysisReused = r.analysisReused;
    stats.factorMs = r.factorMs;
    stats.nnzPerRowL = static_cast<double>(r.factorNonzeros) / std::max(1, topology.numEdges);
    stats.kernelShift = r.kernelShift;
    stats.kernelHandling = r.kernelHandling;
    stats.factorKind = r.factorKind;
  }

  void factorNow() {
    if (baseStale) rebuildBase();
    factor.factor(base, scale, constraintTerms());
    copyFactorReport();
  }

  // Constraint id's rows at relative weight `weight` into (or out of) the factor.
  void updateRows(int32_t id, double weight, bool downdate) {
    DiagonalTerms change;
    constraints.weightedRows(id, weight, scale, change.rows, change.weights);
    factor.update(change, scale, downdate);
    stats.updateMs = factor.lastUpdateMs();
  }

  int32_t add(const ConstraintSpec& spec) {
    const int32_t id = constraints.add(spec);
    stats.rowsMs = constraints.lastRowsMs();
    if (isEdgeKind(spec.kind)) updateRows(id, spec.weight, false);
    return id;
  }
};

Designer::Designer(SurfaceMesh mesh) {
  MeshReport report = checkMesh(mesh);
  if (!report.usable()) throw InputError(report.firstFatal());
  impl_ = std::make_unique<Impl>(std::move(mesh), std::move(*report.topology));
}
Designer::~Designer() = default;
Designer::Designer(Designer&&) noexcept = default;
Designer& Designer::operator=(Designer&&) noexcept = default;

void Designer::setBoundary(const BoundaryCondition& bc) {
  if (!bc.free) {
    requireFinite(bc.angle, "boundary angle");
    boundaryEdgeAngles(impl_->topology, bc);  // validates overrides before anything changes
  }
  if (sameBoundaryCondition(bc, impl_->boundary)) return;  // re-applying a design must not refactor
  impl_->boundary = bc;
  impl_->baseStale = true;
  impl_->factor.invalidate();
}

void Designer::setGamma(double gamma) {
  requireGamma(gamma);
  if (gamma == impl_->gamma) return;
  impl_->gamma = gamma;
  impl_->baseStale = true;
  impl_->factor.invalidate();
}

void Designer::setFactorMemoryLimit(double bytes) {
  if (!std::isfinite(bytes) || bytes < 0) throw InputError("the factor memory limit must be a number >= 0");
  impl_->factor.setMemoryLimit(bytes);
}

double Designer::factorMemoryLimit() const {
  return impl_->factor.memoryLimit();
}

int32_t Designer::precisionRefactors() const {
  return impl_->factor.precisionRefactors();
}

void Designer::setMetisOrdering(bool metis) {
  impl_->factor.setOrdering(metis ? FillOrdering::Metis : FillOrdering::Amd);
}

void Designer::setSolverThreads(int threads) {
  impl_->factor.setThreads(threads);
}

int Designer::solverThreads() const {
  return impl_->factor.threads();
}

void Designer::factor() {
  impl_->factorNow();
}

int32_t Designer::add(const ConstraintSpec& spec) {
  return impl_->add(spec);
}

int32_t Designer::addStroke(const std::vector<SurfacePoint>& points, double strength, double weight) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Stroke;
  s.points = points;
  s.strength = strength;
  s.weight = weight;
  return impl_->add(s);
}

int32_t Designer::addVector(int32_t face, const double vector[3], double weight) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Vector;
  s.element = face;
  std::copy(vector, vector + 3, s.vector);
  s.weight = weight;
  return impl_->add(s);
}

int32_t Designer::addEdge(int32_t i, int32_t j, double value, double weight) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Edge;
  s.edge[0] = i;
  s.edge[1] = j;
  s.value = value;
  s.weight = weight;
  return impl_->add(s);
}

int32_t Designer::addSource(int32_t vertex, double strength) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Source;
  s.element = vertex;
  s.strength = strength;
  return impl_->add(s);
}

int32_t Designer::addSink(int32_t vertex, double strength) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Sink;
  s.element = vertex;
  s.strength = strength;
  return impl_->add(s);
}

int32_t Designer::addVortex(int32_t face, double strength) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Vortex;
  s.element = face;
  s.strength = strength;
  return impl_->add(s);
}

void Designer::remove(int32_t id) {
  Impl& d = *impl_;
  const ConstraintSpec& spec = d.constraints.spec(id);  // throws for an unknown id
  if (isEdgeKind(spec.kind)) d.updateRows(id, spec.weight, true);
  d.constraints.remove(id);
}

void Designer::setWeight(int32_t id, double weight) {
  Impl& d = *impl_;
  const double previous = d.constraints.setWeight(id, weight);  // validates
  const double change = weight - previous;
  if (change == 0) return;
  d.updateRows(id, std::abs(change), change < 0);
}

void Designer::setStrength(int32_t id, double strength) {
  impl_->constraints.setStrength(id, strength);  // enters only the right-hand side
}

void Designer::clearConstraints() {
  Impl& d = *impl_;
  d.factor.update(d.constraintTerms(), d.scale, true);  // one multi-column downdate: the base is unchanged
  d.stats.updateMs = d.factor.lastUpdateMs();
  d.constraints.clear();
}

void Designer::solve() {
  Impl& d = *impl_;
  if (d.baseStale || !d.factor.current()) d.factorNow();
  auto start = Clock::now();
  const Eigen::VectorXd b = d.constraints.rightHandSide(d.ops, d.scale);
  d.stats.rhsMs = msSince(start);
  if (!b.allFinite()) throw InputError("the constraints give a right-hand side that is not finite");
  d.stats.warnings = d.constraints.warnings(d.boundary);
  start = Clock::now();
  Eigen::VectorXd x;
  d.factor.solve(d.base, d.scale, d.constraintTerms(), b, x);
  d.stats.solveMs = msSince(start);
  d.stats.precisionRefactors = d.factor.precisionRefactors();
  d.stats.incrementalSolves = d.factor.incrementalSolves();
  d.stats.supernodalSolves = d.factor.supernodalSolves();
  d.copyFactorReport();  // the solve refactors when an updated factor lost precision
  if (!x.allFinite())
    throw InputError(
        "the field is not finite (the system is too badly conditioned for these constraints); "
        "the previous field is kept");
  start = Clock::now();
  std::vector<double> faceVectors;
  if (d.faceVectorMap.coefficient.empty()) d.faceVectorMap = tvf::faceVectorMap(d.mesh, d.topology);
  tvf::faceVectors(d.faceVectorMap, d.topology, x.data(), faceVectors);
  for (const double v : faceVectors)
    if (!std::isfinite(v))
      throw InputError(
          "the field's vectors are not finite (magnitudes beyond double range on this mesh); "
          "the previous field is kept");
  d.solution = std::move(x);
  d.oneForm.assign(d.solution.data(), d.solution.data() + d.solution.size());
  d.faceVectors = std::move(faceVectors);
  d.stats.reconstructMs = msSince(start);
  d.vertexVectorsStale = d.singularitiesStale = true;
}

const std::vector<double>& Designer::oneForm() const {
  return impl_->oneForm;
}
const std::vector<double>& Designer::faceVectors() const {
  return impl_->faceVectors;
}
// Vertex vectors and singularities are derived on first read: the interactive loop needs only face vectors.
const std::vector<double>& Designer::vertexVectors() const {
  Impl& d = *impl_;
  if (d.vertexVectorsStale) {
    if (d.vertexVectorMap.empty()) d.vertexVectorMap = tvf::vertexVectorMap(d.mesh, d.topology, d.geometry);
    tvf::vertexVectors(d.vertexVectorMap, d.oneForm.data(), d.vertexVectors);
  }
  d.vertexVectorsStale = false;
  return d.vertexVectors;
}
const std::vector<Singularity>& Designer::singularities() const {
  Impl& d = *impl_;
  if (d.singularitiesStale)
    d.singularities = findSingularities(d.mesh, d.topology, d.geometry, d.faceVectors);
  d.singularitiesStale = false;
  return d.singularities;
}
const DesignStats& Designer::stats() const {
  return impl_->stats;
}
HodgeDecomposition Designer::hodgeDecomposition() const {
  const Impl& d = *impl_;
  if (d.oneForm.size() != static_cast<size_t>(d.topology.numEdges))
    throw InputError("no field to decompose: solve first");
  return hodgeDecompose(exteriorDerivative0(d.topology), exteriorDerivative1(d.topology), d.geometry,
                        Eigen::Map<const Eigen::VectorXd>(d.oneForm.data(), d.topology.numEdges));
}
std::vector<ConstraintSpec> Designer::constraints() const {
  return impl_->constraints.specs();
}
const BoundaryCondition& Designer::boundary() const {
  return impl_->boundary;
}
double Designer::gamma() const {
  return impl_->gamma;
}
const SurfaceMesh& Designer::mesh() const {
  return impl_->mesh;
}
const std::vector<int32_t>& Designer::edgeVertices() const {
  return impl_->topology.edgeVertices;
}
const MeshTopology& Designer::topology() const {
  return impl_->topology;
}
const MeshGeometry& Designer::geometry() const {
  return impl_->geometry;
}

void Designer::assembleSystem(SparseMatrix& A, Eigen::VectorXd& b) {
  Impl& d = *impl_;
  if (d.baseStale) d.rebuildBase();
  A = plusDiagonal(d.base, d.constraintTerms());
  b = d.constraints.rightHandSide(d.ops, d.scale);
}

const SparseMatrix& Designer::baseMatrix() {
  if (impl_->baseStale) impl_->rebuildBase();
  return impl_->base;
}

double Designer::weightScale() {
  if (impl_->baseStale) impl_->rebuildBase();
  return impl_->scale;
}

Eigen::VectorXd Designer::textureFaceVectors() const {
  std::vector<double> out;
  tvf::textureFaceVectors(impl_->mesh, impl_->topology, impl_->oneForm.data(), out);
  return Eigen::Map<Eigen::VectorXd>(out.data(), out.size());
}

}  // namespace tvf
