#include "design/prescribed_field_system.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <string>
#include <utility>

#include "common/angles.h"
#include "common/input_error.h"
#include "common/stopwatch.h"
#include "design/direction_field_system.h"
#include "direction/direction_constraints.h"
#include "direction/free_singularities.h"
#include "direction/representative_directions.h"
#include "field/singularities.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

const char* const kField = "a field with prescribed singularities";
// The share of pi / N a prescribed index may turn the field across an edge of its vertex.
constexpr double kTurningShare = 0.8;

// The largest share of a vertex's turning one of its edges takes: 1/w_e over the sum of 1/w around the vertex
// (w the smoothness weight of direction/levi_civita_connection.h, 1.5 |e|^2 / (A_f + A_g)).
double largestShare(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g, int32_t v) {
  double sum = 0, largest = 0;
  for (int32_t i = t.vertexEdgeStart[v]; i < t.vertexEdgeStart[v + 1]; ++i) {
    const int32_t e = t.vertexEdgeList[i], f = t.edgeFaces[2 * e], h = t.edgeFaces[2 * e + 1];
    if (f < 0 || h < 0) continue;
    const double length2 = edgeVector(mesh, t, e).squaredNorm();
    const double inverse = length2 > 0 ? (g.faceArea[f] + g.faceArea[h]) / (1.5 * length2) : 0.0;
    sum += inverse;
    largest = std::max(largest, inverse);
  }
  return sum > 0 ? largest / sum : 1.0;
}

std::string indexText(double index, int symmetry) {
  const long numerator = std::lround(index * symmetry);
  std::string text = (numerator > 0 ? "+" : "") + std::to_string(numerator);
  return symmetry == 1 ? text : text + "/" + std::to_string(symmetry);
}

}  // namespace

void checkSingularity(const ConstraintSpec& spec, int symmetry, const SurfaceMesh& mesh,
                      const MeshTopology& t, const MeshGeometry& g, const ConstraintSet& constraints,
                      int32_t ignoreId) {
  const int32_t v = spec.element;
  const std::string where = "singularity at vertex " + std::to_string(v);
  if (v < 0 || v >= t.numVertices || t.vertexFaceCount[v] == 0)
    throw InputError(where + ": the vertex does not exist or no face uses it");
  if (t.isBoundaryVertex[v])
    throw InputError(where +
                     ": a boundary vertex has no index (the boundary condition sets the field there)");
  const double scaled = spec.value * symmetry;
  if (!std::isfinite(spec.value) || std::abs(scaled - std::round(scaled)) > 1e-9 || std::round(scaled) == 0 ||
      std::abs(spec.value) > 8)
    throw InputError(where + ": the index must be a nonzero multiple of 1/" + std::to_string(symmetry) +
                     " (at most 8 in size) for a field of symmetry " + std::to_string(symmetry) + "; got " +
                     std::to_string(spec.value));
  // The index count (field/singularities.h) sees each edge's turning modulo 2 pi / N: the turning around the
  // one-ring, 2 pi k - K_v, shares out over its edges about as their inverse smoothness weights do (the
  // rotations are W^-1 C' lambda), and the largest share must stay below pi / N or the singularity shows at a
  // neighbour instead.
  const double turning = std::abs(2 * kPi * spec.value - g.angleDefect[v]);
  const double largest = turning * largestShare(mesh, t, g, v);
  if (largest >= kTurningShare * kPi / symmetry)
    throw InputError(where + ": index " + indexText(spec.value, symmetry) + " turns the field by " +
                     std::to_string(std::lround(turning * 180 / kPi)) + " degrees around its " +
                     std::to_string(t.vertexFaceCount[v]) + " edges (its angle defect included), up to " +
                     std::to_string(std::lround(largest * 180 / kPi)) +
                     " degrees across one, too much for a " + "field of symmetry " +
                     std::to_string(symmetry) + " to show it there: choose a vertex with " +
                     "more neighbours, or refine the mesh");
  for (const ConstraintSpec& other : constraints.specsOf(ConstraintKind::Singularity))
    if (other.element == v && other.id != ignoreId && other.id != spec.id)
      throw InputError(where + ": the vertex already has a prescribed singularity (index " +
                       indexText(other.value, symmetry) + "); move or remove that one");
}

void checkOffFeatureCurves(int32_t vertex, const MeshTopology& t, const std::vector<int32_t>& featureEdges) {
  int count = 0;
  for (const int32_t e : featureEdges)
    count += t.edgeVertices[2 * e] == vertex || t.edgeVertices[2 * e + 1] == vertex;
  if (count == 2)
    throw InputError(
        "singularity at vertex " + std::to_string(vertex) +
        ": the vertex lies inside a sharp feature curve, along which the field is held; prescribe it "
        "off the curve or where curves meet, or remove the feature there");
}

PrescribedFieldSystem::PrescribedFieldSystem(int symmetry, const DesignMesh& mesh, ConstraintSet& constraints,
                                             const FieldSettings& settings)
    : symmetry_(symmetry),
      mesh_(mesh),
      constraints_(constraints),
      settings_(settings),
      gamma_(settings.gamma),
      frames_(mesh.faceFrames()),
      trivial_(mesh.topology(), mesh.leviCivitaConnection()),
      angles_(mesh.topology(), mesh.leviCivitaConnection(), symmetry) {
  refuseVectorNotions(constraints.specs(), kField);
  for (const ConstraintSpec& spec : constraints.specsOf(ConstraintKind::Singularity))
    checkSingularity(spec, symmetry, mesh.mesh(), mesh.topology(), mesh.geometry(), constraints);
  configureFactor(angles_.factor(), settings);
  fixedTerms();
  addAll();
}

ShiftedFactor& PrescribedFieldSystem::factor() {
  return angles_.factor();
}

int64_t PrescribedFieldSystem::unknowns() const {
  return mesh_.topology().numFaces;
}

PowerFieldSystem& PrescribedFieldSystem::power() {
  if (!power_) {
    power_ = std::make_unique<PowerFieldSystem>(mesh_.mesh(), mesh_.topology(), mesh_.geometry(), frames_,
                                                mesh_.leviCivitaConnection(), symmetry_);
    configureFactor(power_->factor(), settings_);
    if (symmetry_ % 2 == 0) power_->setCurvatureAlignment(settings_.curvatureAlignment);
    // Its own base only: the angle system's factor stays as it is.
    power_->setBoundaryTerms(
        fixedDirectionTerms(mesh_, settings_.boundary, settings_.featureEdges, symmetry_), kBoundaryWeight);
    for (const ConstraintSpec& spec : constraints_.specs())
      if (spec.kind == ConstraintKind::Stroke || spec.kind == ConstraintKind::Vector)
        power_->add(spec.id, directionTerms(mesh_.mesh(), mesh_.topology(), frames_, spec, symmetry_),
                    spec.weight);
  }
  return *power_;
}

void PrescribedFieldSystem::fixedTerms() {
  std::vector<FaceDirectionTerm> all =
      fixedDirectionTerms(mesh_, settings_.boundary, settings_.featureEdges, symmetry_);
  angles_.setFixedTerms(all, kBoundaryWeight);
  if (power_) power_->setBoundaryTerms(std::move(all), kBoundaryWeight);
  naturalChanged();
}

void PrescribedFieldSystem::naturalChanged() {
  naturalStale_ = true;
  if (!exact_) connectionStale_ = true;  // the free singularities follow the smoothest field's
}

void PrescribedFieldSystem::seedSmoothestSingularities(std::map<int32_t, double> singularities) {
  natural_ = std::move(singularities);
  naturalStale_ = false;
  connectionStale_ = true;
}

// The singularities of the smoothest field of the design without its prescriptions.
const std::map<int32_t, double>& PrescribedFieldSystem::natural() {
  if (!naturalStale_) return natural_;
  Eigen::VectorXd u;
  power().solve(u);
  const std::vector<double> vectors = faceRepresentatives(frames_, u, symmetry_);
  natural_.clear();
  for (const Singularity& s :
       findSingularities(mesh_.mesh(), mesh_.topology(), mesh_.geometry(), vectors, symmetry_))
    natural_[s.vertex] = s.index;
  naturalStale_ = false;
  return natural_;
}

void PrescribedFieldSystem::setBoundary(const BoundaryCondition& bc) {
  settings_.boundary = bc;
  fixedTerms();
}

void PrescribedFieldSystem::setFeatures(const std::vector<int32_t>& edges) {
  settings_.featureEdges = edges;
  fixedTerms();
}

void PrescribedFieldSystem::setCurvatureAlignment(double s) {
  settings_.curvatureAlignment = s;
  if (power_ && symmetry_ % 2 == 0) power_->setCurvatureAlignment(s);
  naturalChanged();
}

void PrescribedFieldSystem::addAll() {
  for (const ConstraintSpec& spec : constraints_.specs())
    if (spec.kind == ConstraintKind::Stroke || spec.kind == ConstraintKind::Vector) {
      std::vector<FaceDirectionTerm> terms =
          directionTerms(mesh_.mesh(), mesh_.topology(), frames_, spec, symmetry_);
      if (power_) power_->add(spec.id, terms, spec.weight);
      angles_.add(spec.id, std::move(terms), spec.weight);
    }
  naturalStale_ = connectionStale_ = true;
}

void PrescribedFieldSystem::resume() {
  refuseVectorNotions(constraints_.specs(), kField);
  for (const ConstraintSpec& spec : constraints_.specsOf(ConstraintKind::Singularity))
    checkSingularity(spec, symmetry_, mesh_.mesh(), mesh_.topology(), mesh_.geometry(), constraints_);
  angles_.factor().invalidate();
  angles_.clear();
  if (power_) {
    power_->factor().invalidate();
    power_->clear();
  }
  addAll();
}

int32_t PrescribedFieldSystem::add(const ConstraintSpec& spec, DesignStats& stats) {
  if (spec.kind == ConstraintKind::Singularity) {
    checkSingularity(spec, symmetry_, mesh_.mesh(), mesh_.topology(), mesh_.geometry(), constraints_);
    const int32_t id = constraints_.add(spec);
    connectionStale_ = true;
    return id;
  }
  ConstraintSpec probe = spec;
  probe.id = 0;
  constraints_.validate(probe);
  const auto start = Clock::now();
  std::vector<FaceDirectionTerm> terms =
      directionTerms(mesh_.mesh(), mesh_.topology(), frames_, spec, symmetry_);  // throws naming the kind
  stats.rowsMs = msSince(start);
  const int32_t id = constraints_.add(spec);
  if (power_) power_->add(id, terms, spec.weight);
  angles_.add(id, std::move(terms), spec.weight);
  stats.updateMs = factor().lastUpdateMs();
  naturalChanged();
  return id;
}

void PrescribedFieldSystem::remove(const ConstraintSpec& spec, DesignStats& stats) {
  if (spec.kind == ConstraintKind::Singularity) {
    connectionStale_ = true;
    return;
  }
  angles_.remove(spec.id);
  if (power_) power_->remove(spec.id);
  stats.updateMs = factor().lastUpdateMs();
  naturalChanged();
}

void PrescribedFieldSystem::reweight(const ConstraintSpec& spec, double, DesignStats&) {
  angles_.setWeight(spec.id, spec.weight);
  if (power_) power_->setWeight(spec.id, spec.weight);
  naturalChanged();
}

void PrescribedFieldSystem::clear(DesignStats& stats) {
  angles_.clear();
  if (power_) power_->clear();
  naturalStale_ = connectionStale_ = true;
  stats.updateMs = factor().lastUpdateMs();
}

std::map<int32_t, double> PrescribedFieldSystem::prescribed() const {
  std::map<int32_t, double> out;
  for (const ConstraintSpec& spec : constraints_.specsOf(ConstraintKind::Singularity))
    out[spec.element] = spec.value;
  return out;
}

// The free singularities, when the prescribed ones do not complete the index, and the trivial connection's
// parallel field for both.
void PrescribedFieldSystem::updateConnection(DesignStats& stats) {
  if (!connectionStale_) return;
  const MeshTopology& t = mesh_.topology();
  const std::map<int32_t, double> indices = prescribed();
  exact_ = indicesComplete(t, indices);
  free_ = exact_ ? std::map<int32_t, double>{}
                 : tvf::freeSingularities(mesh_.mesh(), t, natural(), indices, symmetry_);
  std::map<int32_t, double> all = indices;
  all.insert(free_.begin(), free_.end());
  rotations_ = trivial_.rotations(holonomyTargets(t, mesh_.geometry(), all), symmetry_);
  stats.connectionMs = trivial_.lastSolveMs();
  angles_.setParallel(trivial_.parallelAngles(rotations_));
  connectionStale_ = false;
}

void PrescribedFieldSystem::factorNow(DesignStats& stats) {
  updateConnection(stats);
  angles_.factorNow();
  stats.nnzPerRowM = angles_.nonZerosPerRow();
}

void PrescribedFieldSystem::solve(FieldSolution& field, DesignStats& stats) {
  updateConnection(stats);
  auto start = Clock::now();
  std::vector<double> theta;
  angles_.solve(theta);
  Eigen::VectorXd u(2 * static_cast<Eigen::Index>(theta.size()));
  for (size_t f = 0; f < theta.size(); ++f) {
    const std::complex<double> z = std::polar(1.0, symmetry_ * theta[f]);
    u[2 * f] = z.real();
    u[2 * f + 1] = z.imag();
  }
  stats.solveMs = msSince(start);
  reportFactor(factor(), unknowns(), stats);
  stats.nnzPerRowM = angles_.nonZerosPerRow();
  stats.inverseIterations = 0;
  stats.smoothestEigenvalue = 0;
  stats.rhsMs = 0;
  stats.warnings.clear();
  if (gamma_ > 0) stats.warnings.push_back("gamma applies to vector fields without prescribed singularities");
  if (settings_.curvatureAlignment > 0 && exact_)
    stats.warnings.push_back(
        "curvature alignment only moves the free singularities; these are all prescribed");
  if (!u.allFinite())
    throw InputError(
        "the field is not finite (the system is too badly conditioned for these constraints); "
        "the previous field is kept");
  start = Clock::now();
  field.faceVectors = faceRepresentatives(frames_, u, symmetry_);
  field.unknowns = std::move(u);
  field.oneForm.clear();
  field.symmetry = symmetry_;
  field.prescribed = prescribed();
  stats.reconstructMs = msSince(start);

  double sum = 0;
  for (const auto& [v, index] : field.prescribed) sum += index;
  stats.singularityMode = exact_ ? "exact" : "free";
  stats.eulerCharacteristic = mesh_.topology().eulerCharacteristic();
  stats.prescribedIndex = sum;
  stats.freeIndex = stats.eulerCharacteristic - sum;
}

void PrescribedFieldSystem::vertexVectors(const FieldSolution& field, std::vector<double>& out) const {
  vertexRepresentatives(mesh_.vertexTangentAxes(), mesh_.mesh(), mesh_.topology(), mesh_.geometry(),
                        field.faceVectors, symmetry_, out);
}

void PrescribedFieldSystem::assemble(SparseMatrix& A, Eigen::VectorXd& b) {
  DesignStats ignored;
  updateConnection(ignored);
  angles_.assemble(A, b);
}

SparseMatrix PrescribedFieldSystem::baseMatrix() {
  return angles_.baseMatrix();
}

double PrescribedFieldSystem::weightScale() {
  return angles_.scale();
}

}  // namespace tvf
