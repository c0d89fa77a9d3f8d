#include "design/designer.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "constraints/edge_rows.h"
#include "constraints/singular_sources.h"
#include "dec/boundary_condition.h"
#include "dec/one_form_laplacian.h"
#include "design/mesh_info.h"
#include "field/singularities.h"
#include "field/whitney_reconstruction.h"
#include "mesh/mesh_checks.h"
#include "solver/factored_system.h"

namespace tvf {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The kernel of M (harmonic fields, and more with free boundaries) is made definite by a diagonal shift this
// small relative to the mean diagonal; it is raised only if CHOLMOD still finds a non-positive pivot.
constexpr double kInitialShift = 1e-9;
constexpr double kMaxShift = 1e-4;
// Fixed-angle boundary rows are enforced this strongly relative to the mean diagonal.
constexpr double kBoundaryWeight = 1e4;
// A downdate that removes weight w (relative to the mean diagonal) leaves round-off of about eps * w in the
// pivots it passes through: removing a 1e20 weight leaves nothing of the original pivot (all NaN), removing
// 1e8 leaves 1e-8. The weights taken out by downdates since the last factorization are summed; a downdate
// that would push the sum past this budget refactors instead, which keeps the factor within ~1e-12 of a
// fresh one.
constexpr double kDowndateBudget = 1e4;
// Backward error of a solve with an updated factor beyond which the factor is considered spoilt (a fresh
// LDL' gives ~1e-15).
constexpr double kUpdatedResidualTolerance = 1e-10;

bool isEdgeKind(ConstraintKind k) {
  return k == ConstraintKind::Stroke || k == ConstraintKind::Vector || k == ConstraintKind::Edge;
}

bool sameBoundary(const BoundaryCondition& a, const BoundaryCondition& b) {
  if (a.free != b.free) return false;
  if (a.free) return true;
  if (a.angle != b.angle || a.perEdge.size() != b.perEdge.size()) return false;
  for (size_t k = 0; k < a.perEdge.size(); ++k)
    if (a.perEdge[k].i != b.perEdge[k].i || a.perEdge[k].j != b.perEdge[k].j ||
        a.perEdge[k].angle != b.perEdge[k].angle)
      return false;
  return true;
}

void requireFinite(double x, const char* what) {
  if (!std::isfinite(x)) throw InputError(std::string(what) + " must be a finite number");
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

void requireMagnitude(double x, const char* what) {
  requireFinite(x, what);
  if (std::abs(x) > kMaxMagnitude)
    throw InputError(std::string(what) + " " + number(x) +
                     " is out of range (|x| <= " + number(kMaxMagnitude) + ")");
}

void requireWeight(double w) {
  if (!std::isfinite(w) || !(w >= kMinWeight && w <= kMaxWeight))
    throw InputError("a constraint's weight must be a number from " + number(kMinWeight) + " to " +
                     number(kMaxWeight) + " (got " + number(w) + ")");
}

double physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
  return pages > 0 && pageSize > 0 ? static_cast<double>(pages) * static_cast<double>(pageSize) : 0.0;
}

bool allFinite(const Eigen::VectorXd& x) {
  return x.allFinite();
}

}  // namespace

BoundaryCondition BoundaryCondition::tangential() {
  return fixedAngle(M_PI / 2);
}

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

  FactoredSystem system;
  bool factorStale = true;
  double memoryLimit = 0;           // 0: physical memory
  double downdateLoad = 0;          // relative weight removed by downdates since the last factorization
  bool updatedSinceFactor = false;  // the factor is no longer the one CHOLMOD computed from scratch
  int32_t precisionRefactors = 0;
  double shift = kInitialShift;
  bool shiftEverywhere = false;

  struct Active {
    ConstraintSpec spec;
    std::vector<EdgeRow> rows;  // edge-type constraints, values for unit strength
  };
  std::map<int32_t, Active> active;  // ids only grow, so map order is insertion order
  int32_t nextId = 1;

  Eigen::VectorXd solution;
  std::vector<double> oneForm, faceVectors, vertexVectors;
  std::vector<Singularity> singularities;
  // Derived on first read, each on its own: the page's default view needs the vertex vectors only.
  bool vertexVectorsStale = false, singularitiesStale = false;
  VertexVectorMap vertexVectorMap;  // built on first use (geometry only)
  FaceVectorMap faceVectorMap;      // likewise
  DesignStats stats;

  void rebuildBase() {
    const std::vector<double> angles = boundaryEdgeAngles(topology, boundary);
    ops = buildOneFormOperators(mesh, topology, geometry, angles);
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
    factorStale = true;
  }

  // Weighted constraint rows sqrt(w) e_i as (row, weight) lists.
  void weightedRows(const Active& a, double weight, std::vector<int32_t>& rows,
                    std::vector<double>& w) const {
    for (const EdgeRow& r : a.rows) {
      rows.push_back(r.edge);
      w.push_back(weight * scale);
    }
  }

  // Closed genus-0 components have no kernel; every other component (handles, boundary loops, and the extra
  // modes of free boundaries) gets the shift.
  bool componentHasKernel(int32_t c) const {
    return topology.components[c].genus > 0 || topology.components[c].boundaryLoops > 0;
  }

  SparseMatrix systemMatrix(double relativeShift, bool everywhere) const {
    std::vector<Eigen::Triplet<double, int>> diag;
    for (int32_t e = 0; e < topology.numEdges; ++e)
      if (everywhere || componentHasKernel(topology.edgeComponent[e]))
        diag.emplace_back(e, e, relativeShift * scale);
    for (const auto& [id, a] : active)
      if (isEdgeKind(a.spec.kind))
        for (const EdgeRow& r : a.rows) diag.emplace_back(r.edge, r.edge, a.spec.weight * scale);
    SparseMatrix D(topology.numEdges, topology.numEdges);
    D.setFromTriplets(diag.begin(), diag.end());
    return base + D;
  }

  void factorNow() {
    if (baseStale) rebuildBase();
    int retries = 0;
    bool anyKernel = false;
    for (int32_t c = 0; c < static_cast<int32_t>(topology.components.size()); ++c)
      anyKernel |= componentHasKernel(c);
    shiftEverywhere = false;
    shift = anyKernel ? kInitialShift : 0.0;
    system.setMemoryLimit(memoryLimit > 0 ? memoryLimit : physicalMemoryBytes());
    while (!system.factor(systemMatrix(shift, shiftEverywhere))) {
      // Numerically singular despite the topology (e.g. a near-kernel on a badly shaped closed mesh).
      ++retries;
      shift = shiftEverywhere ? shift * 100 : kInitialShift;
      shiftEverywhere = true;
      if (shift > kMaxShift)
        throw InputError("the system could not be factored even with a diagonal shift of " +
                         std::to_string(shift / 100) + " (is the mesh badly shaped?)");
    }
    const FactorTimings& t = system.timings();
    stats.analyzeMs = t.analyzeMs;
    stats.analysisReused = t.analysisReused;
    stats.factorMs = t.factorMs + t.convertMs;
    stats.nnzPerRowL = static_cast<double>(system.factorNonzeros()) / std::max(1, topology.numEdges);
    stats.kernelShift = shift;
    char text[240];
    if (shift == 0)
      std::snprintf(text, sizeof text, "none needed: every component is closed and of genus 0");
    else
      std::snprintf(text, sizeof text,
                    "diagonal shift %.0e x mean diagonal on the edges of %s, then one step of iterative "
                    "refinement against the unshifted matrix; %d retries",
                    shift, shiftEverywhere ? "every component" : "components with handles or boundary",
                    retries);
    stats.kernelHandling = text;
    stats.factorKind = system.description();
    factorStale = false;
    downdateLoad = 0;
    updatedSinceFactor = false;
  }

  void applyUpdate(const std::vector<int32_t>& rows, const std::vector<double>& w, bool downdate) {
    if (factorStale || rows.empty()) return;  // the next factorization includes the change
    if (downdate) {
      double largest = 0;
      for (const double wk : w) largest = std::max(largest, wk / scale);
      if (downdateLoad + largest > kDowndateBudget) {
        factorStale = true;  // refactor at the next solve instead of downdating away the precision
        return;
      }
      downdateLoad += largest;
    }
    updatedSinceFactor = true;
    const auto start = Clock::now();
    system.updateDiagonal(rows, w, downdate);
    stats.updateMs = msSince(start);
  }

  // The shift biases the solution by O(shift / smallest nonzero eigenvalue), and fully for fields that only
  // constraints pin down (a constant field on a free-boundary patch lies in the kernel of M). One step of
  // iterative refinement against the unshifted matrix cuts that to O(shift^2) for one more solve; kernel
  // components the design leaves free stay at the minimum-norm choice.
  void refineAgainstUnshiftedSystem(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    Eigen::VectorXd residual = b - base * x;
    for (const auto& [id, a] : active)
      if (isEdgeKind(a.spec.kind))
        for (const EdgeRow& r : a.rows) residual[r.edge] -= a.spec.weight * scale * x[r.edge];
    Eigen::VectorXd correction;
    system.solve(residual, correction);
    x += correction;
  }

  // The matrix the factor holds (base + shift + constraint rows) times x.
  Eigen::VectorXd factoredProduct(const Eigen::VectorXd& x) const {
    Eigen::VectorXd y = base * x;
    if (shift > 0)
      for (int32_t e = 0; e < topology.numEdges; ++e)
        if (shiftEverywhere || componentHasKernel(topology.edgeComponent[e])) y[e] += shift * scale * x[e];
    for (const auto& [id, a] : active)
      if (isEdgeKind(a.spec.kind))
        for (const EdgeRow& r : a.rows) y[r.edge] += a.spec.weight * scale * x[r.edge];
    return y;
  }

  // Solves with the current factor (plus the refinement step); an updated factor whose solution is not
  // finite or whose backward error is beyond round-off is replaced by a fresh factorization, once.
  void checkedSolve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    system.solve(b, x);
    if (updatedSinceFactor) {
      const Eigen::VectorXd y = factoredProduct(x);
      const double residual = (b - y).norm(), size = b.norm() + y.norm();
      if (!allFinite(x) || !std::isfinite(residual) || residual > kUpdatedResidualTolerance * size) {
        ++precisionRefactors;
        factorNow();
        system.solve(b, x);
      }
    }
    if (shift > 0 && allFinite(x)) refineAgainstUnshiftedSystem(b, x);
  }

  Eigen::VectorXd rightHandSide() const {
    SourceTargets targets = singularTargets(topology, geometry, specsOf(ConstraintKind::Source),
                                            specsOf(ConstraintKind::Sink), specsOf(ConstraintKind::Vortex));
    Eigen::VectorXd b = ops.d1.transpose() * (geometry.star2.asDiagonal() * targets.curl) +
                        ops.divergence.transpose() * targets.divergence;
    for (const auto& [id, a] : active)
      if (isEdgeKind(a.spec.kind))
        for (const EdgeRow& r : a.rows) b[r.edge] += a.spec.weight * scale * a.spec.strength * r.value;
    return b;
  }

  // Under a fixed-angle boundary, boundary vertices take no part in the divergence term: a source or sink
  // there has no effect, which the user should hear about rather than guess.
  std::vector<std::string> designWarnings() const {
    std::vector<std::string> out;
    if (boundary.free) return out;
    for (const auto& [id, a] : active)
      if ((a.spec.kind == ConstraintKind::Source || a.spec.kind == ConstraintKind::Sink) &&
          topology.isBoundaryVertex[a.spec.element])
        out.push_back("constraint " + std::to_string(id) + ": a source or sink on boundary vertex " +
                      std::to_string(a.spec.element) +
                      " has no effect under a fixed-angle boundary condition");
    return out;
  }

  std::vector<ConstraintSpec> specsOf(ConstraintKind kind) const {
    std::vector<ConstraintSpec> out;
    for (const auto& [id, a] : active)
      if (a.spec.kind == kind) out.push_back(a.spec);
    return out;
  }

  void validate(const ConstraintSpec& s) const {
    const auto faceOk = [&](int32_t f) { return f >= 0 && f < topology.numFaces; };
    const auto vertexOk = [&](int32_t v) {
      return v >= 0 && v < topology.numVertices && topology.vertexFaceCount[v] > 0;
    };
    requireMagnitude(s.strength, "strength");
    requireFinite(s.weight, "weight");
    if (isEdgeKind(s.kind)) requireWeight(s.weight);
    switch (s.kind) {
      case ConstraintKind::Vector:
        if (!faceOk(s.element))
          throw InputError("vector constraint: face " + std::to_string(s.element) + " does not exist");
        for (const double x : s.vector) requireMagnitude(x, "vector component");
        break;
      case ConstraintKind::Vortex:
        if (!faceOk(s.element))
          throw InputError("vortex: face " + std::to_string(s.element) + " does not exist");
        break;
      case ConstraintKind::Source:
      case ConstraintKind::Sink:
        if (!vertexOk(s.element))
          throw InputError("source/sink: vertex " + std::to_string(s.element) +
                           " does not exist or is unused");
        break;
      case ConstraintKind::Edge:
        requireMagnitude(s.value, "edge value");
        if (s.edge[0] == s.edge[1])
          throw InputError("edge constraint: an edge needs two different vertices (got " +
                           std::to_string(s.edge[0]) + " twice)");
        if (findEdge(topology, s.edge[0], s.edge[1]) < 0)
          throw InputError("edge constraint: vertices " + std::to_string(s.edge[0]) + " and " +
                           std::to_string(s.edge[1]) + " are not joined by an edge");
        break;
      case ConstraintKind::Stroke:
        break;  // strokeRows validates its points
    }
  }

  std::vector<EdgeRow> rowsFor(const ConstraintSpec& s) const {
    switch (s.kind) {
      case ConstraintKind::Stroke:
        return strokeRows(mesh, topology, s.points);
      case ConstraintKind::Vector: {
        const Eigen::Vector3d u(s.vector[0], s.vector[1], s.vector[2]);
        return vectorRows(mesh, topology, s.element, u);
      }
      case ConstraintKind::Edge: {
        const int32_t e = findEdge(topology, s.edge[0], s.edge[1]);
        return {{e, s.edge[0] < s.edge[1] ? s.value : -s.value}};
      }
      default:
        return {};
    }
  }

  int32_t add(ConstraintSpec spec) {
    validate(spec);
    const auto start = Clock::now();
    Active a{spec, rowsFor(spec)};
    stats.rowsMs = msSince(start);
    a.spec.id = nextId++;
    std::vector<int32_t> rows;
    std::vector<double> w;
    if (isEdgeKind(spec.kind)) weightedRows(a, spec.weight, rows, w);
    active.emplace(a.spec.id, a);
    applyUpdate(rows, w, false);
    return a.spec.id;
  }

  Active& find(int32_t id) {
    const auto it = active.find(id);
    if (it == active.end()) throw InputError("no constraint with id " + std::to_string(id));
    return it->second;
  }
};

Designer::Designer(SurfaceMesh mesh) : impl_(std::make_unique<Impl>()) {
  const MeshReport report = checkMesh(mesh);
  if (!report.usable()) throw InputError(report.firstFatal());
  impl_->mesh = std::move(mesh);
  impl_->topology = *report.topology;
  impl_->geometry = computeMeshGeometry(impl_->mesh, impl_->topology);
  impl_->stats.positiveAreaFallbackVertices = impl_->geometry.positiveAreaFallbackVertices;
}
Designer::~Designer() = default;
Designer::Designer(Designer&&) noexcept = default;
Designer& Designer::operator=(Designer&&) noexcept = default;

void Designer::setBoundary(const BoundaryCondition& bc) {
  if (!bc.free) {
    requireFinite(bc.angle, "boundary angle");
    boundaryEdgeAngles(impl_->topology, bc);  // validates overrides before anything changes
  }
  if (sameBoundary(bc, impl_->boundary)) return;  // re-applying a design must not refactor
  impl_->boundary = bc;
  impl_->baseStale = true;
  impl_->factorStale = true;
}

void Designer::setGamma(double gamma) {
  if (!std::isfinite(gamma) || gamma < 0 || gamma > kMaxGamma)
    throw InputError("gamma must be a number from 0 to " + number(kMaxGamma) + " (got " + number(gamma) +
                     ")");
  if (gamma == impl_->gamma) return;
  impl_->gamma = gamma;
  impl_->baseStale = true;
  impl_->factorStale = true;
}

void Designer::setFactorMemoryLimit(double bytes) {
  if (!std::isfinite(bytes) || bytes < 0) throw InputError("the factor memory limit must be a number >= 0");
  impl_->memoryLimit = bytes;
}

double Designer::factorMemoryLimit() const {
  return impl_->memoryLimit;
}

int32_t Designer::precisionRefactors() const {
  return impl_->precisionRefactors;
}

void Designer::setMetisOrdering(bool metis) {
  impl_->system = FactoredSystem(metis ? FillOrdering::Metis : FillOrdering::Amd);
  impl_->factorStale = true;
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
  Impl::Active& a = d.find(id);
  std::vector<int32_t> rows;
  std::vector<double> w;
  if (isEdgeKind(a.spec.kind)) d.weightedRows(a, a.spec.weight, rows, w);
  d.applyUpdate(rows, w, true);
  d.active.erase(id);
}

void Designer::setWeight(int32_t id, double weight) {
  Impl& d = *impl_;
  Impl::Active& a = d.find(id);
  if (!isEdgeKind(a.spec.kind)) throw InputError("only strokes, vectors and edge constraints have a weight");
  requireWeight(weight);
  const double change = weight - a.spec.weight;
  if (change == 0) return;
  std::vector<int32_t> rows;
  std::vector<double> w;
  d.weightedRows(a, std::abs(change), rows, w);
  d.applyUpdate(rows, w, change < 0);
  a.spec.weight = weight;
}

void Designer::setStrength(int32_t id, double strength) {
  requireMagnitude(strength, "strength");
  Impl::Active& a = impl_->find(id);
  a.spec.strength = strength;  // enters only the right-hand side
}

void Designer::clearConstraints() {
  Impl& d = *impl_;
  std::vector<int32_t> rows;
  std::vector<double> w;
  for (const auto& [id, a] : d.active)
    if (isEdgeKind(a.spec.kind)) d.weightedRows(a, a.spec.weight, rows, w);
  d.applyUpdate(rows, w, true);  // one multi-column downdate: the base matrix has not changed
  d.active.clear();
}

void Designer::solve() {
  Impl& d = *impl_;
  if (d.baseStale || d.factorStale || !d.system.factored()) d.factorNow();
  auto start = Clock::now();
  const Eigen::VectorXd b = d.rightHandSide();
  d.stats.rhsMs = msSince(start);
  if (!allFinite(b)) throw InputError("the constraints give a right-hand side that is not finite");
  d.stats.warnings = d.designWarnings();
  start = Clock::now();
  Eigen::VectorXd x;
  d.checkedSolve(b, x);
  d.stats.solveMs = msSince(start);
  if (!allFinite(x))
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
    if (d.vertexVectorMap.start.empty())
      d.vertexVectorMap = tvf::vertexVectorMap(d.mesh, d.topology, d.geometry);
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
std::vector<ConstraintSpec> Designer::constraints() const {
  std::vector<ConstraintSpec> specs;
  for (const auto& [id, a] : impl_->active) specs.push_back(a.spec);
  return specs;
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

void Designer::assembleSystem(SparseMatrix& A, Eigen::VectorXd& b) {
  Impl& d = *impl_;
  if (d.baseStale) d.rebuildBase();
  A = d.systemMatrix(0.0, false);
  b = d.rightHandSide();
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

std::string Designer::infoJson() const {
  return meshInfoJson(impl_->mesh).dump();
}

}  // namespace tvf
