#include "design/designer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

#include "constraints/constraint_set.h"
#include "dec/exterior_derivative.h"
#include "dec/one_form_laplacian.h"
#include "direction/power_field_system.h"
#include "direction/representative_directions.h"
#include "field/whitney_reconstruction.h"
#include "mesh/mesh_checks.h"
#include "mesh/mesh_hash.h"
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
  std::optional<uint64_t> meshHash;  // made on first use
  MeshTopology topology;
  std::vector<MeshProblem> meshNotes;  // the check's non-fatal problems
  MeshGeometry geometry;
  BoundaryCondition boundary;
  double gamma = 0;

  // Base system, rebuilt when the boundary condition or gamma change; its upper triangle only.
  bool baseStale = true;
  OneFormOperators ops;
  SparseMatrix base;
  double scale = 1;

  ConstraintSet constraints;
  ShiftedFactor factor;
  // N >= 2: the power-field system that replaces the 1-form's (built when the symmetry is set).
  int symmetry = 1;
  double curvatureAlignment = 0;
  bool metis = true;
  std::unique_ptr<PowerFieldSystem> directions;

  Eigen::VectorXd solution;
  std::vector<double> oneForm, faceVectors, vertexVectors;
  // The solve's reconstruction, swapped in once it is known finite; between solves, scratch
  // (vertexVectors()).
  std::vector<double> nextFaceVectors;
  std::vector<Singularity> singularities;
  // Derived on first read, each on its own: the page's default view needs the vertex vectors only.
  bool vertexVectorsStale = false, singularitiesStale = false;
  VertexVectorMap vertexVectorMap;  // built on first use (geometry only): vertexMap()
  FaceVectorMap faceVectorMap;      // likewise: faceMap()
  const FaceVectorMap& faceMap() {
    if (faceVectorMap.coefficient.empty()) faceVectorMap = tvf::faceVectorMap(mesh, topology);
    return faceVectorMap;
  }
  const VertexVectorMap& vertexMap() {
    if (vertexVectorMap.empty()) vertexVectorMap = tvf::vertexVectorMap(mesh, topology, geometry);
    return vertexVectorMap;
  }
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
    base = SparseMatrix();  // the old one goes before the new one is assembled
    base = gamma > 0 ? upperTriangle(
                           biLaplacian(oneFormLaplacian(ops, geometry), geometry, gamma * geometry.totalArea))
                     : oneFormLaplacianUpper(ops, geometry);
    ops.d0 = SparseMatrix();  // it made the divergence; nothing reads it after (35 MB at 1.25M edges)
    scale = meanDiagonal(base);
    if (ops.boundaryRows.rows() > 0) {
      const SparseMatrix Zt = ops.boundaryRows.transpose();
      base += upperTriangle((kBoundaryWeight * scale) * (Zt * ops.boundaryRows));
      base.makeCompressed();
    }
    const double nonZeros = 2.0 * static_cast<double>(base.nonZeros()) - static_cast<double>(base.rows());
    stats.nnzPerRowM = nonZeros / std::max<Eigen::Index>(1, base.rows());
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
    stats.factorizations = r.factorizations;
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
    if (directions) {
      // Checked (and a stroke walked) before the set changes: a refused constraint leaves nothing behind.
      std::vector<FaceDirectionTerm> terms;
      if (spec.kind == ConstraintKind::Stroke || spec.kind == ConstraintKind::Vector) {
        ConstraintSpec probe = spec;
        probe.id = 0;
        constraints.validate(probe);
        const auto start = Clock::now();
        terms = directionTerms(mesh, topology, directions->frames(), spec, symmetry);
        stats.rowsMs = msSince(start);
      } else {
        directionTerms(mesh, topology, directions->frames(), spec, symmetry);  // throws naming the kind
      }
      const int32_t id = constraints.add(spec);
      directions->add(id, std::move(terms), spec.weight);
      stats.updateMs = directions->lastUpdateMs();
      return id;
    }
    const int32_t id = constraints.add(spec);
    stats.rowsMs = constraints.lastRowsMs();
    if (isEdgeKind(spec.kind)) updateRows(id, spec.weight, false);
    return id;
  }

  void buildDirections() {
    directions.reset();
    if (symmetry == 1) return;
    auto system = std::make_unique<PowerFieldSystem>(mesh, topology, geometry, symmetry);
    system->factor().setOrdering(metis ? FillOrdering::Metis : FillOrdering::Amd);
    system->factor().setThreads(factor.threads());
    system->factor().setMemoryLimit(factor.memoryLimit());
    system->setCurvatureAlignment(curvatureAlignment);
    applyBoundary(*system);
    for (const ConstraintSpec& spec : constraints.specs())
      system->add(spec.id, directionTerms(mesh, topology, system->frames(), spec, symmetry), spec.weight);
    directions = std::move(system);
  }

  void solveDirections();

  // A fixed-angle boundary as strongly weighted directions at the boundary faces (the weight of the 1-form's
  // fixed-angle rows); a free boundary adds none.
  void applyBoundary(PowerFieldSystem& system) {
    const std::vector<double> angles =
        boundary.free ? std::vector<double>{} : boundaryEdgeAngles(topology, boundary);
    system.setBoundaryTerms(boundaryDirectionTerms(mesh, topology, system.frames(), angles, symmetry),
                            kBoundaryWeight);
  }
};

void Designer::Impl::solveDirections() {
  auto start = Clock::now();
  Eigen::VectorXd u;
  directions->solve(u);
  stats.solveMs = msSince(start);
  ShiftedFactor& f = directions->factor();
  const FactorReport& r = f.report();
  stats.analyzeMs = r.analyzeMs;
  stats.analysisReused = r.analysisReused;
  stats.factorMs = r.factorMs;
  stats.nnzPerRowL = static_cast<double>(r.factorNonzeros) / std::max(1, 2 * topology.numFaces);
  stats.kernelShift = r.kernelShift;
  stats.kernelHandling = r.kernelHandling;
  stats.factorKind = r.factorKind;
  stats.factorizations = r.factorizations;
  stats.precisionRefactors = f.precisionRefactors();
  stats.incrementalSolves = f.incrementalSolves();
  stats.supernodalSolves = f.supernodalSolves();
  stats.inverseIterations = directions->report().inverseIterations;
  stats.smoothestEigenvalue = directions->report().eigenvalue;
  stats.rhsMs = 0;
  stats.warnings.clear();
  if (gamma > 0)
    stats.warnings.push_back("gamma applies to vector fields (symmetry 1); this field ignores it");
  if (!u.allFinite())
    throw InputError(
        "the field is not finite (the system is too badly conditioned for these constraints); "
        "the previous field is kept");
  start = Clock::now();
  faceVectors = faceRepresentatives(directions->frames(), u, symmetry);
  solution = std::move(u);
  oneForm.clear();
  stats.reconstructMs = msSince(start);
  stats.symmetry = symmetry;
  vertexVectorsStale = singularitiesStale = true;
}

Designer::Designer(SurfaceMesh mesh) {
  MeshReport report = checkMesh(mesh);
  if (!report.usable()) throw InputError(report.firstFatal());
  impl_ = std::make_unique<Impl>(std::move(mesh), std::move(*report.topology));
  impl_->meshNotes = std::move(report.problems);
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
  if (impl_->directions) impl_->applyBoundary(*impl_->directions);
}

void Designer::setGamma(double gamma) {
  requireGamma(gamma);
  if (gamma == impl_->gamma) return;
  impl_->gamma = gamma;
  impl_->baseStale = true;
  impl_->factor.invalidate();
}

void Designer::setSymmetry(int symmetry) {
  Impl& d = *impl_;
  if (symmetry < 1 || symmetry > 6)
    throw InputError("the symmetry must be an integer from 1 to 6 (1 vector, 2 line, 4 cross field); got " +
                     std::to_string(symmetry));
  if (symmetry == d.symmetry) return;
  if (symmetry > 1) {
    int sources = 0, sinks = 0, vortices = 0, edges = 0;
    for (const ConstraintSpec& spec : d.constraints.specs()) {
      sources += spec.kind == ConstraintKind::Source;
      sinks += spec.kind == ConstraintKind::Sink;
      vortices += spec.kind == ConstraintKind::Vortex;
      edges += spec.kind == ConstraintKind::Edge;
    }
    std::string named;
    auto name = [&](int count, const char* one, const char* many) {
      if (count == 0) return;
      named += (named.empty() ? "" : ", ") + std::to_string(count) + " " + (count == 1 ? one : many);
    };
    name(sources, "source", "sources");
    name(sinks, "sink", "sinks");
    name(vortices, "vortex", "vortices");
    name(edges, "edge value", "edge values");
    if (!named.empty())
      throw InputError("a field of symmetry " + std::to_string(symmetry) +
                       " takes strokes and directions only; the design has " + named +
                       " (vector-field notions): remove them first");
  }
  if (symmetry > 1 && symmetry % 2 != 0 && d.curvatureAlignment > 0)
    throw InputError("curvature alignment needs an even symmetry; turn it off before choosing symmetry " +
                     std::to_string(symmetry));
  const int previous = d.symmetry;
  d.symmetry = symmetry;
  try {
    d.buildDirections();
  } catch (...) {
    d.symmetry = previous;
    d.buildDirections();
    throw;
  }
  if (symmetry == 1) d.factor.invalidate();  // rows may have come and gone while it was not in use
  d.oneForm.clear();
  d.faceVectors.clear();
  d.vertexVectors.clear();
  d.singularities.clear();
  d.vertexVectorsStale = d.singularitiesStale = false;
}

int Designer::symmetry() const {
  return impl_->symmetry;
}

void Designer::setCurvatureAlignment(double s) {
  Impl& d = *impl_;
  if (!std::isfinite(s) || s < 0 || s > 1e6)
    throw InputError("the curvature alignment must be a number from 0 to 1e6 (0: off)");
  if (s > 0 && (d.symmetry == 1 || d.symmetry % 2 != 0))
    throw InputError("curvature alignment is for line and cross fields (an even symmetry); the symmetry is " +
                     std::to_string(d.symmetry));
  if (d.directions) d.directions->setCurvatureAlignment(s);
  d.curvatureAlignment = s;
}

double Designer::curvatureAlignment() const {
  return impl_->curvatureAlignment;
}

void Designer::setFactorMemoryLimit(double bytes) {
  if (!std::isfinite(bytes) || bytes < 0) throw InputError("the factor memory limit must be a number >= 0");
  impl_->factor.setMemoryLimit(bytes);
  if (impl_->directions) impl_->directions->factor().setMemoryLimit(bytes);
}

double Designer::factorMemoryLimit() const {
  return impl_->factor.memoryLimit();
}

int32_t Designer::precisionRefactors() const {
  return impl_->factor.precisionRefactors();
}

void Designer::setMetisOrdering(bool metis) {
  impl_->factor.setOrdering(metis ? FillOrdering::Metis : FillOrdering::Amd);
  impl_->metis = metis;
  if (impl_->directions)
    impl_->directions->factor().setOrdering(metis ? FillOrdering::Metis : FillOrdering::Amd);
}

void Designer::setSolverThreads(int threads) {
  impl_->factor.setThreads(threads);
  if (impl_->directions) impl_->directions->factor().setThreads(threads);
}

int Designer::solverThreads() const {
  return impl_->factor.threads();
}

void Designer::setDeferredUpdates(bool defer) {
  impl_->factor.setDeferredUpdates(defer);
}

void Designer::applyDeferredUpdates() {
  impl_->factor.applyDeferred();
  impl_->stats.deferredUpdateMs = impl_->factor.lastDeferredUpdateMs();
}

void Designer::factor() {
  if (impl_->directions) {
    impl_->directions->factor().invalidate();
    impl_->solveDirections();  // factors; the solve after it is what a caller wants next anyway
    return;
  }
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
  if (d.directions) {
    d.directions->remove(id);
    d.stats.updateMs = d.directions->lastUpdateMs();
  } else if (isEdgeKind(spec.kind)) {
    d.updateRows(id, spec.weight, true);
  }
  d.constraints.remove(id);
}

void Designer::setWeight(int32_t id, double weight) {
  Impl& d = *impl_;
  const double previous = d.constraints.setWeight(id, weight);  // validates
  const double change = weight - previous;
  if (change == 0) return;
  if (d.directions) return d.directions->setWeight(id, weight);
  d.updateRows(id, std::abs(change), change < 0);
}

void Designer::setStrength(int32_t id, double strength) {
  impl_->constraints.setStrength(id, strength);  // enters only the right-hand side
}

void Designer::clearConstraints() {
  Impl& d = *impl_;
  if (d.directions) {
    d.directions->clear();
    d.stats.updateMs = d.directions->lastUpdateMs();
    d.constraints.clear();
    d.factor.invalidate();  // the 1-form factor no longer holds these rows
    return;
  }
  d.factor.update(d.constraintTerms(), d.scale, true);  // one multi-column downdate: the base is unchanged
  d.stats.updateMs = d.factor.lastUpdateMs();
  d.constraints.clear();
}

void Designer::solve() {
  Impl& d = *impl_;
  if (d.directions) return d.solveDirections();
  d.stats.symmetry = 1;
  d.stats.inverseIterations = 0;
  d.stats.smoothestEigenvalue = 0;
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
  std::vector<double>& faceVectors = d.nextFaceVectors;
  tvf::faceVectors(d.faceMap(), d.topology, x.data(), faceVectors);
  for (const double v : faceVectors)
    if (!std::isfinite(v))
      throw InputError(
          "the field's vectors are not finite (magnitudes beyond double range on this mesh); "
          "the previous field is kept");
  d.solution = std::move(x);
  d.oneForm.assign(d.solution.data(), d.solution.data() + d.solution.size());
  std::swap(d.faceVectors, faceVectors);
  d.stats.reconstructMs = msSince(start);
  d.vertexVectorsStale = d.singularitiesStale = true;
}

const std::vector<double>& Designer::oneForm() const {
  return impl_->oneForm;
}
const std::vector<double>& Designer::faceVectors() const {
  return impl_->faceVectors;
}
void Designer::reconstruct(const double* oneForm, std::vector<double>& faceVectors,
                           std::vector<double>& vertexVectors) const {
  Impl& d = *impl_;
  tvf::faceVectors(d.faceMap(), d.topology, oneForm, faceVectors);
  tvf::vertexVectors(d.vertexMap(), d.faceMap(), d.mesh, d.topology, d.geometry, oneForm, vertexVectors);
}
// Vertex vectors and singularities are derived on first read: the interactive loop needs only face vectors.
const std::vector<double>& Designer::vertexVectors() const {
  Impl& d = *impl_;
  if (d.vertexVectorsStale && d.directions) {
    d.vertexVectors = vertexRepresentatives(d.mesh, d.topology, d.geometry, d.faceVectors, d.symmetry);
  } else if (d.vertexVectorsStale) {
    // The solve's spare face array (the previous field's, 3 doubles per face) holds the threads' partial
    // sums.
    tvf::vertexVectors(d.vertexMap(), d.faceMap(), d.mesh, d.topology, d.geometry, d.oneForm.data(),
                       d.vertexVectors, d.nextFaceVectors);
  }
  d.vertexVectorsStale = false;
  return d.vertexVectors;
}
const std::vector<Singularity>& Designer::singularities() const {
  Impl& d = *impl_;
  if (d.singularitiesStale)
    d.singularities = findSingularities(d.mesh, d.topology, d.geometry, d.faceVectors, d.symmetry);
  d.singularitiesStale = false;
  return d.singularities;
}
const DesignStats& Designer::stats() const {
  return impl_->stats;
}
HodgeDecomposition Designer::hodgeDecomposition() const {
  const Impl& d = *impl_;
  if (d.directions)
    throw InputError("the Hodge decomposition is of vector fields (symmetry 1); this field has symmetry " +
                     std::to_string(d.symmetry));
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
uint64_t Designer::meshHash() const {
  if (!impl_->meshHash) impl_->meshHash = tvf::meshHash(impl_->mesh);
  return *impl_->meshHash;
}
const std::vector<int32_t>& Designer::edgeVertices() const {
  return impl_->topology.edgeVertices;
}
const std::vector<MeshProblem>& Designer::meshNotes() const {
  return impl_->meshNotes;
}

const MeshTopology& Designer::topology() const {
  return impl_->topology;
}
const MeshGeometry& Designer::geometry() const {
  return impl_->geometry;
}

void Designer::assembleSystem(SparseMatrix& A, Eigen::VectorXd& b) {
  Impl& d = *impl_;
  if (d.directions) return d.directions->assemble(A, b);
  if (d.baseStale) d.rebuildBase();
  A = plusDiagonal(fullFromUpper(d.base), d.constraintTerms());
  b = d.constraints.rightHandSide(d.ops, d.scale);
}

SparseMatrix Designer::baseMatrix() {
  if (impl_->baseStale) impl_->rebuildBase();
  return fullFromUpper(impl_->base);
}

double Designer::weightScale() {
  if (impl_->baseStale) impl_->rebuildBase();
  return impl_->scale;
}

Eigen::VectorXd Designer::textureFaceVectors() const {
  if (impl_->directions)
    throw InputError("texture vectors are of vector fields (symmetry 1); this field has symmetry " +
                     std::to_string(impl_->symmetry));
  std::vector<double> out;
  tvf::textureFaceVectors(impl_->mesh, impl_->topology, impl_->oneForm.data(), out);
  return Eigen::Map<Eigen::VectorXd>(out.data(), out.size());
}

}  // namespace tvf
