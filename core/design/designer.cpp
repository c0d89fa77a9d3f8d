#include "design/designer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "common/input_error.h"
#include "constraints/constraint_set.h"
#include "dec/exterior_derivative.h"
#include "design/derived_field.h"
#include "design/design_mesh.h"
#include "design/field_system.h"
#include "design/prescribed_field_system.h"
#include "field/whitney_reconstruction.h"
#include "mesh/feature_edges.h"
#include "mesh/mesh_checks.h"

namespace tvf {
namespace {

// Read-outs that only a vector field has (a 1-form): refused by name for an N-direction field.
void requireVectorField(const FieldSystem& system, const char* what) {
  if (system.symmetry() == 1 && system.prescribes())
    throw InputError(
        std::string(what) +
        " of a vector field's 1-form; with prescribed singularities the field is a unit direction "
        "field (no 1-form): remove the singularities first");
  const int symmetry = system.symmetry();
  if (symmetry != 1)
    throw InputError(std::string(what) + " of vector fields (symmetry 1); this field has symmetry " +
                     std::to_string(symmetry));
}

}  // namespace

struct Designer::Impl {
  DesignMesh mesh;
  std::vector<MeshProblem> meshNotes;  // the check's non-fatal problems
  ConstraintSet constraints;
  FieldSettings settings;
  std::unique_ptr<FieldSystem> system;
  // The system in use before the last symmetry change, resumed when that symmetry comes back: its factor's
  // ordering (the analysis) is kept, its numeric factor freed.
  std::unique_ptr<FieldSystem> retired;
  DerivedField field;
  // The field is the solve of the design as it is (no edit since): what a new system may start from.
  bool fieldCurrent = false;
  bool unseenChecked = true;  // the solve's prescriptions compared with the singularities it shows
  DesignStats stats;
  double featureAngle = 0;
  std::vector<std::array<int32_t, 2>> featureAdded, featureRemoved;

  Impl(SurfaceMesh m, MeshTopology t)
      : mesh(std::move(m), std::move(t)), constraints(mesh.mesh(), mesh.topology(), mesh.geometry()) {
    system = makeFieldSystem(1, mesh, constraints, settings);
    stats.positiveAreaFallbackVertices = mesh.geometry().positiveAreaFallbackVertices;
  }

  int symmetry() const { return system->symmetry(); }

  // A setting every system follows, the retired one too, so that resuming it needs no catching up.
  template <typename Apply>
  void eachSystem(Apply apply) {
    apply(*system);
    if (retired) apply(*retired);
  }

  // A singularity's checks against the mesh, the symmetry, the other prescriptions (but the one with id
  // ignoreId, being moved) and the features; throws InputError naming the problem.
  void checkPrescription(const ConstraintSpec& spec, int32_t ignoreId = 0) const {
    constraints.validate(spec);
    checkSingularity(spec, symmetry(), mesh.mesh(), mesh.topology(), mesh.geometry(), constraints, ignoreId);
    checkOffFeatureCurves(spec.element, mesh.topology(), settings.featureEdges);
  }

  bool wantsPrescribed() const {
    return settings.exactSingularities || !constraints.specsOf(ConstraintKind::Singularity).empty();
  }

  // The system for this symmetry and the constraint set as it is (with or without prescribed singularities).
  void switchTo(int symmetry) {
    fieldCurrent = false;
    std::unique_ptr<FieldSystem> next;
    if (retired && retired->symmetry() == symmetry && retired->prescribes() == wantsPrescribed()) {
      retired->resume();  // throws, retired unchanged, for constraints it cannot take
      next = std::move(retired);
    } else {
      next = makeFieldSystem(symmetry, mesh, constraints, settings);
    }
    retired = std::move(system);
    // Resuming it factors it again (its constraints may change meanwhile): only its ordering is worth
    // keeping, and its factor would double the memory of a big mesh's design (3.64 against 1.79 GB at 1.25M
    // edges with a cross field).
    retired->factor().release();
    system = std::move(next);
    field.clear();
  }
};

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
  Impl& d = *impl_;
  if (!bc.free) {
    requireFinite(bc.angle, "boundary angle");
    boundaryEdgeAngles(d.mesh.topology(), bc);  // validates overrides before anything changes
  }
  if (sameBoundaryCondition(bc, d.settings.boundary)) return;  // re-applying a design must not refactor
  d.settings.boundary = bc;
  d.fieldCurrent = false;
  d.eachSystem([&](FieldSystem& s) { s.setBoundary(bc); });
}

void Designer::setGamma(double gamma) {
  Impl& d = *impl_;
  requireGamma(gamma);
  if (gamma == d.settings.gamma) return;
  d.settings.gamma = gamma;
  d.eachSystem([&](FieldSystem& s) { s.setGamma(gamma); });
}

void Designer::setSymmetry(int symmetry) {
  Impl& d = *impl_;
  if (symmetry < 1 || symmetry > 6)
    throw InputError("the symmetry must be an integer from 1 to 6 (1 vector, 2 line, 4 cross field); got " +
                     std::to_string(symmetry));
  if (symmetry == d.symmetry()) return;
  if (symmetry > 1 && symmetry % 2 != 0 && d.settings.curvatureAlignment > 0)
    throw InputError("curvature alignment needs an even symmetry; turn it off before choosing symmetry " +
                     std::to_string(symmetry));
  d.switchTo(symmetry);
}

int Designer::symmetry() const {
  return impl_->symmetry();
}

void Designer::setCurvatureAlignment(double s) {
  Impl& d = *impl_;
  if (!std::isfinite(s) || s < 0 || s > 1e6)
    throw InputError("the curvature alignment must be a number from 0 to 1e6 (0: off)");
  if (s > 0 && (d.symmetry() == 1 || d.symmetry() % 2 != 0))
    throw InputError("curvature alignment is for line and cross fields (an even symmetry); the symmetry is " +
                     std::to_string(d.symmetry()));
  d.settings.curvatureAlignment = s;
  d.fieldCurrent = false;
  // A retired odd symmetry cannot come back with the alignment on (setSymmetry refuses it): it needs none.
  d.eachSystem([&](FieldSystem& f) {
    if (s == 0 || f.symmetry() % 2 == 0) f.setCurvatureAlignment(s);
  });
}

double Designer::curvatureAlignment() const {
  return impl_->settings.curvatureAlignment;
}

void Designer::setFactorMemoryLimit(double bytes) {
  if (!std::isfinite(bytes) || bytes < 0) throw InputError("the factor memory limit must be a number >= 0");
  impl_->settings.memoryLimit = bytes;
  impl_->eachSystem([&](FieldSystem& s) { s.factor().setMemoryLimit(bytes); });
}

double Designer::factorMemoryLimit() const {
  return impl_->system->factor().memoryLimit();
}

int32_t Designer::precisionRefactors() const {
  return impl_->system->factor().precisionRefactors();
}

void Designer::setMetisOrdering(bool metis) {
  const FillOrdering ordering = metis ? FillOrdering::Metis : FillOrdering::Amd;
  impl_->settings.ordering = ordering;
  impl_->eachSystem([&](FieldSystem& s) { s.factor().setOrdering(ordering); });
}

void Designer::setSolverThreads(int threads) {
  impl_->settings.threads = threads;
  impl_->eachSystem([&](FieldSystem& s) { s.factor().setThreads(threads); });
}

int Designer::solverThreads() const {
  return impl_->system->factor().threads();
}

void Designer::setDeferredUpdates(bool defer) {
  impl_->settings.deferUpdates = defer;
  impl_->eachSystem([&](FieldSystem& s) { s.factor().setDeferredUpdates(defer); });
}

void Designer::applyDeferredUpdates() {
  ShiftedFactor& factor = impl_->system->factor();
  factor.applyDeferred();
  impl_->stats.deferredUpdateMs = factor.lastDeferredUpdateMs();
}

void Designer::factor() {
  Impl& d = *impl_;
  d.system->factorNow(d.stats);
  reportFactor(d.system->factor(), d.system->unknowns(), d.stats);
}

int32_t Designer::add(const ConstraintSpec& spec) {
  Impl& d = *impl_;
  if (spec.kind != ConstraintKind::Singularity || d.system->prescribes()) {
    if (spec.kind == ConstraintKind::Singularity)
      checkOffFeatureCurves(spec.element, d.mesh.topology(), d.settings.featureEdges);
    const int32_t id = d.system->add(spec, d.stats);
    d.fieldCurrent = false;
    return id;
  }
  // The first singularity: the design's field becomes the prescribed-singularity system's, which places the
  // rest of the index where the field it replaces has its singularities.
  ConstraintSpec probe = spec;
  probe.id = 0;
  d.checkPrescription(probe);
  std::map<int32_t, double> smoothest;
  const bool seed = d.fieldCurrent && !d.field.solution().faceVectors.empty();
  if (seed)
    for (const Singularity& s : d.field.requireSingularities(d.mesh)) smoothest[s.vertex] = s.index;
  const int32_t id = d.constraints.add(spec);
  try {
    d.switchTo(d.symmetry());
  } catch (...) {
    d.constraints.remove(id);
    throw;
  }
  if (seed) d.system->seedSmoothestSingularities(std::move(smoothest));
  d.fieldCurrent = false;
  return id;
}

void Designer::setExactSingularities(bool exact) {
  Impl& d = *impl_;
  if (exact == d.settings.exactSingularities) return;
  d.settings.exactSingularities = exact;
  if (d.system->prescribes() == d.wantsPrescribed()) return;
  try {
    d.switchTo(d.symmetry());
  } catch (...) {
    d.settings.exactSingularities = !exact;
    throw;
  }
}

bool Designer::exactSingularities() const {
  return impl_->settings.exactSingularities;
}

int32_t Designer::addSingularity(int32_t vertex, double index) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Singularity;
  s.element = vertex;
  s.value = index;
  return add(s);
}

void Designer::moveSingularity(int32_t id, int32_t vertex) {
  Impl& d = *impl_;
  ConstraintSpec moved = d.constraints.spec(id);  // throws for an unknown id
  if (moved.kind != ConstraintKind::Singularity)
    throw InputError("constraint " + std::to_string(id) + " is not a singularity; only singularities move");
  moved.element = vertex;
  d.checkPrescription(moved, id);
  d.constraints.setElement(id, vertex);
  d.fieldCurrent = false;
  d.system->singularitiesChanged();
}

void Designer::setFeatures(double degrees, const std::vector<std::array<int32_t, 2>>& add,
                           const std::vector<std::array<int32_t, 2>>& remove) {
  Impl& d = *impl_;
  std::vector<int32_t> edges = tvf::featureEdges(d.mesh.topology(), d.mesh.geometry(), degrees, add, remove);
  for (const ConstraintSpec& s : d.constraints.specsOf(ConstraintKind::Singularity))
    checkOffFeatureCurves(s.element, d.mesh.topology(), edges);
  d.featureAngle = degrees;
  d.featureAdded = add;
  d.featureRemoved = remove;
  if (edges == d.settings.featureEdges) return;  // re-applying a design must not refactor
  d.settings.featureEdges = std::move(edges);
  d.fieldCurrent = false;
  d.eachSystem([&](FieldSystem& s) { s.setFeatures(d.settings.featureEdges); });
}

double Designer::featureAngle() const {
  return impl_->featureAngle;
}
const std::vector<std::array<int32_t, 2>>& Designer::featureEdgesAdded() const {
  return impl_->featureAdded;
}
const std::vector<std::array<int32_t, 2>>& Designer::featureEdgesRemoved() const {
  return impl_->featureRemoved;
}
const std::vector<int32_t>& Designer::featureEdges() const {
  return impl_->settings.featureEdges;
}

int32_t Designer::addStroke(const std::vector<SurfacePoint>& points, double strength, double weight) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Stroke;
  s.points = points;
  s.strength = strength;
  s.weight = weight;
  return add(s);
}

int32_t Designer::addVector(int32_t face, const double vector[3], double weight) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Vector;
  s.element = face;
  std::copy(vector, vector + 3, s.vector);
  s.weight = weight;
  return add(s);
}

int32_t Designer::addEdge(int32_t i, int32_t j, double value, double weight) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Edge;
  s.edge[0] = i;
  s.edge[1] = j;
  s.value = value;
  s.weight = weight;
  return add(s);
}

int32_t Designer::addSource(int32_t vertex, double strength) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Source;
  s.element = vertex;
  s.strength = strength;
  return add(s);
}

int32_t Designer::addSink(int32_t vertex, double strength) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Sink;
  s.element = vertex;
  s.strength = strength;
  return add(s);
}

int32_t Designer::addVortex(int32_t face, double strength) {
  ConstraintSpec s;
  s.kind = ConstraintKind::Vortex;
  s.element = face;
  s.strength = strength;
  return add(s);
}

void Designer::remove(int32_t id) {
  Impl& d = *impl_;
  const ConstraintSpec spec = d.constraints.spec(id);  // throws for an unknown id
  d.fieldCurrent = false;
  d.system->remove(spec, d.stats);
  d.constraints.remove(id);
  // The last singularity gone: back to the symmetry's own system (resumed when it was retired).
  if (d.system->prescribes() != d.wantsPrescribed()) d.switchTo(d.symmetry());
}

void Designer::setWeight(int32_t id, double weight) {
  Impl& d = *impl_;
  const double previous = d.constraints.setWeight(id, weight);  // validates
  if (weight == previous) return;
  d.fieldCurrent = false;
  d.system->reweight(d.constraints.spec(id), previous, d.stats);
}

void Designer::setStrength(int32_t id, double strength) {
  impl_->constraints.setStrength(id, strength);  // enters only the right-hand side
  impl_->fieldCurrent = false;
}

void Designer::clearConstraints() {
  Impl& d = *impl_;
  d.fieldCurrent = false;
  d.system->clear(d.stats);
  d.constraints.clear();
  if (d.system->prescribes() != d.wantsPrescribed()) d.switchTo(d.symmetry());
}

void Designer::solve() {
  Impl& d = *impl_;
  d.stats.symmetry = d.symmetry();
  if (!d.system->prescribes()) {
    d.stats.singularityMode = "none";
    d.stats.prescribedIndex = 0;
    d.stats.eulerCharacteristic = d.mesh.topology().eulerCharacteristic();
    d.stats.freeIndex = d.stats.eulerCharacteristic;
  }
  d.stats.featureEdges = static_cast<int32_t>(d.settings.featureEdges.size());
  d.system->solve(d.field.solution(), d.stats);
  if (!d.system->prescribes()) d.field.solution().prescribed.clear();
  d.unseenChecked = false;
  d.fieldCurrent = true;
  d.field.solved();
}

const std::vector<double>& Designer::oneForm() const {
  return impl_->field.solution().oneForm;
}
const std::vector<double>& Designer::faceVectors() const {
  return impl_->field.solution().faceVectors;
}
void Designer::reconstruct(const double* oneForm, std::vector<double>& faceVectors,
                           std::vector<double>& vertexVectors) const {
  const DesignMesh& m = impl_->mesh;
  tvf::faceVectors(m.faceVectorMap(), m.topology(), oneForm, faceVectors);
  tvf::vertexVectors(m.vertexVectorMap(), m.faceVectorMap(), m.mesh(), m.topology(), m.geometry(), oneForm,
                     vertexVectors);
}
const std::vector<double>& Designer::vertexVectors() const {
  return impl_->field.requireVertexVectors(*impl_->system);
}
const std::vector<Singularity>& Designer::singularities() const {
  Impl& d = *impl_;
  const std::vector<Singularity>& found = d.field.requireSingularities(d.mesh);
  if (!d.unseenChecked) {
    // A prescription the index count does not find (a stroke or a feature turning the field too fast beside
    // it) is named rather than silently lost; checked once per solve, when the singularities are first read.
    d.unseenChecked = true;
    for (const auto& [v, index] : d.field.solution().prescribed) {
      bool shown = false;
      for (const Singularity& s : found) shown = shown || (s.vertex == v && s.prescribed);
      if (!shown)
        d.stats.warnings.push_back("the singularity prescribed at vertex " + std::to_string(v) + " (index " +
                                   std::to_string(index) +
                                   ") does not show: a stroke, direction or feature turns the field too fast "
                                   "beside it");
    }
  }
  return found;
}
const DesignStats& Designer::stats() const {
  return impl_->stats;
}
HodgeDecomposition Designer::hodgeDecomposition() const {
  const Impl& d = *impl_;
  requireVectorField(*d.system, "the Hodge decomposition is");
  const std::vector<double>& oneForm = d.field.solution().oneForm;
  const MeshTopology& topology = d.mesh.topology();
  if (oneForm.size() != static_cast<size_t>(topology.numEdges))
    throw InputError("no field to decompose: solve first");
  return hodgeDecompose(exteriorDerivative0(topology), exteriorDerivative1(topology), d.mesh.geometry(),
                        Eigen::Map<const Eigen::VectorXd>(oneForm.data(), topology.numEdges));
}
std::vector<ConstraintSpec> Designer::constraints() const {
  return impl_->constraints.specs();
}
const BoundaryCondition& Designer::boundary() const {
  return impl_->settings.boundary;
}
double Designer::gamma() const {
  return impl_->settings.gamma;
}
const SurfaceMesh& Designer::mesh() const {
  return impl_->mesh.mesh();
}
uint64_t Designer::meshHash() const {
  return impl_->mesh.hash();
}

KeptOrdering Designer::fieldOrdering() const {
  return impl_->system->factor().keptOrdering();
}

bool Designer::adoptFieldOrdering(KeptOrdering kept) {
  return impl_->system->factor().adoptOrdering(std::move(kept));
}

void Designer::keepFieldSymbolic(bool keep) {
  impl_->system->factor().setKeepSymbolic(keep);
}

bool Designer::fieldOrderingIsNew() const {
  return impl_->system->factor().keptOrderingIsNew();
}

void Designer::prepareSystem() {
  impl_->system->prepareBase();
}

void Designer::releaseFactors() {
  impl_->eachSystem([](FieldSystem& s) { s.releaseMemory(); });
}
const std::vector<int32_t>& Designer::edgeVertices() const {
  return impl_->mesh.topology().edgeVertices;
}
const std::vector<MeshProblem>& Designer::meshNotes() const {
  return impl_->meshNotes;
}
const MeshTopology& Designer::topology() const {
  return impl_->mesh.topology();
}
const MeshGeometry& Designer::geometry() const {
  return impl_->mesh.geometry();
}
const std::vector<double>& Designer::vertexNormals() const {
  return impl_->mesh.vertexNormals();
}
const FoldProfile& Designer::foldProfile() const {
  return impl_->mesh.foldProfile();
}
double Designer::suggestedFeatureAngle() const {
  return tvf::suggestedFeatureAngle(foldProfile());
}

void Designer::assembleSystem(SparseMatrix& A, Eigen::VectorXd& b) {
  impl_->system->assemble(A, b);
}

SparseMatrix Designer::baseMatrix() {
  return impl_->system->baseMatrix();
}

double Designer::weightScale() {
  return impl_->system->weightScale();
}

Eigen::VectorXd Designer::textureFaceVectors() const {
  const Impl& d = *impl_;
  requireVectorField(*d.system, "texture vectors are");
  std::vector<double> out;
  tvf::textureFaceVectors(d.mesh.mesh(), d.mesh.topology(), d.field.solution().oneForm.data(), out);
  return Eigen::Map<Eigen::VectorXd>(out.data(), out.size());
}

}  // namespace tvf
