#include "design/direction_field_system.h"

#include <chrono>
#include <string>
#include <utility>

#include "common/input_error.h"
#include "common/stopwatch.h"
#include "direction/direction_constraints.h"
#include "direction/feature_terms.h"
#include "direction/representative_directions.h"

namespace tvf {

// Sources, sinks, vortices and edge values are vector-field notions: the refusal names how many of each the
// design holds, so the user knows what to remove.
void refuseVectorNotions(const std::vector<ConstraintSpec>& specs, const std::string& field) {
  int sources = 0, sinks = 0, vortices = 0, edges = 0;
  for (const ConstraintSpec& spec : specs) {
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
    throw InputError(field + " takes strokes and directions only; the design has " + named +
                     " (vector-field notions): remove them first");
}

namespace {
std::string symmetryField(int symmetry) {
  return "a field of symmetry " + std::to_string(symmetry);
}
}  // namespace

DirectionFieldSystem::DirectionFieldSystem(int symmetry, const DesignMesh& mesh, ConstraintSet& constraints,
                                           const FieldSettings& settings)
    : symmetry_(symmetry),
      mesh_(mesh),
      constraints_(constraints),
      gamma_(settings.gamma),
      system_(mesh.mesh(), mesh.topology(), mesh.geometry(), mesh.faceFrames(), mesh.leviCivitaConnection(),
              symmetry) {
  refuseVectorNotions(constraints.specs(), symmetryField(symmetry));
  configureFactor(system_.factor(), settings);
  system_.setCurvatureAlignment(settings.curvatureAlignment);
  boundary_ = settings.boundary;
  featureEdges_ = settings.featureEdges;
  fixedTerms();
  addAll();
}

int64_t DirectionFieldSystem::unknowns() const {
  return 2 * static_cast<int64_t>(mesh_.topology().numFaces);
}

std::vector<FaceDirectionTerm> fixedDirectionTerms(const DesignMesh& mesh, const BoundaryCondition& boundary,
                                                   const std::vector<int32_t>& featureEdges, int symmetry) {
  const std::vector<double> angles =
      boundary.free ? std::vector<double>{} : boundaryEdgeAngles(mesh.topology(), boundary);
  std::vector<FaceDirectionTerm> terms =
      boundaryDirectionTerms(mesh.mesh(), mesh.topology(), mesh.faceFrames(), angles, symmetry);
  if (featureEdges.empty()) return terms;
  const std::vector<FaceDirectionTerm> features =
      featureDirectionTerms(mesh.mesh(), mesh.topology(), mesh.faceFrames(),
                            featureCurves(mesh.topology(), featureEdges), symmetry);
  terms.insert(terms.end(), features.begin(), features.end());
  return terms;
}

void DirectionFieldSystem::setBoundary(const BoundaryCondition& bc) {
  boundary_ = bc;
  fixedTerms();
}

void DirectionFieldSystem::setFeatures(const std::vector<int32_t>& edges) {
  featureEdges_ = edges;
  fixedTerms();
}

void DirectionFieldSystem::fixedTerms() {
  system_.setBoundaryTerms(fixedDirectionTerms(mesh_, boundary_, featureEdges_, symmetry_), kBoundaryWeight);
}

void DirectionFieldSystem::addAll() {
  for (const ConstraintSpec& spec : constraints_.specs())
    system_.add(spec.id, directionTerms(mesh_.mesh(), mesh_.topology(), system_.frames(), spec, symmetry_),
                spec.weight);
}

void DirectionFieldSystem::resume() {
  refuseVectorNotions(constraints_.specs(), symmetryField(symmetry_));
  system_.factor().invalidate();  // so that forgetting the old terms downdates nothing
  system_.clear();
  addAll();
}

int32_t DirectionFieldSystem::add(const ConstraintSpec& spec, DesignStats& stats) {
  // Checked (and a stroke walked) before the set changes: a refused constraint leaves nothing behind.
  std::vector<FaceDirectionTerm> terms;
  if (spec.kind == ConstraintKind::Stroke || spec.kind == ConstraintKind::Vector) {
    ConstraintSpec probe = spec;
    probe.id = 0;
    constraints_.validate(probe);
    const auto start = Clock::now();
    terms = directionTerms(mesh_.mesh(), mesh_.topology(), system_.frames(), spec, symmetry_);
    stats.rowsMs = msSince(start);
  } else {
    directionTerms(mesh_.mesh(), mesh_.topology(), system_.frames(), spec,
                   symmetry_);  // throws naming the kind
  }
  const int32_t id = constraints_.add(spec);
  system_.add(id, std::move(terms), spec.weight);
  stats.updateMs = system_.lastUpdateMs();
  return id;
}

void DirectionFieldSystem::remove(const ConstraintSpec& spec, DesignStats& stats) {
  system_.remove(spec.id);
  stats.updateMs = system_.lastUpdateMs();
}

void DirectionFieldSystem::reweight(const ConstraintSpec& spec, double, DesignStats&) {
  system_.setWeight(spec.id, spec.weight);
}

void DirectionFieldSystem::clear(DesignStats& stats) {
  system_.clear();
  stats.updateMs = system_.lastUpdateMs();
}

void DirectionFieldSystem::factorNow(DesignStats& stats) {
  system_.factorNow();
  stats.nnzPerRowM = system_.nonZerosPerRow();
}

void DirectionFieldSystem::solve(FieldSolution& field, DesignStats& stats) {
  auto start = Clock::now();
  Eigen::VectorXd u;
  system_.solve(u);
  stats.solveMs = msSince(start);
  reportFactor(system_.factor(), unknowns(), stats);
  stats.nnzPerRowM = system_.nonZerosPerRow();
  stats.inverseIterations = system_.report().inverseIterations;
  stats.smoothestEigenvalue = system_.report().eigenvalue;
  stats.rhsMs = 0;
  stats.warnings.clear();
  if (gamma_ > 0)
    stats.warnings.push_back("gamma applies to vector fields (symmetry 1); this field ignores it");
  if (!u.allFinite())
    throw InputError(
        "the field is not finite (the system is too badly conditioned for these constraints); "
        "the previous field is kept");
  start = Clock::now();
  field.faceVectors = faceRepresentatives(system_.frames(), u, symmetry_);
  field.unknowns = std::move(u);
  field.oneForm.clear();
  field.symmetry = symmetry_;
  stats.reconstructMs = msSince(start);
}

void DirectionFieldSystem::vertexVectors(const FieldSolution& field, std::vector<double>& out) const {
  vertexRepresentatives(mesh_.vertexTangentAxes(), mesh_.mesh(), mesh_.topology(), mesh_.geometry(),
                        field.faceVectors, symmetry_, out);
}

}  // namespace tvf
