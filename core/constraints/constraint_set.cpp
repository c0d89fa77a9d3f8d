#include "constraints/constraint_set.h"

#include <chrono>
#include <utility>

#include "common/input_error.h"
#include "common/numeric_ranges.h"
#include "constraints/singular_sources.h"

namespace tvf {
namespace {

bool isSingularKind(ConstraintKind k) {
  return k == ConstraintKind::Source || k == ConstraintKind::Sink || k == ConstraintKind::Vortex;
}

}  // namespace

ConstraintSet::ConstraintSet(const SurfaceMesh& mesh, const MeshTopology& topology,
                             const MeshGeometry& geometry)
    : mesh_(mesh), topology_(topology), geometry_(geometry) {}

void ConstraintSet::validate(const ConstraintSpec& s) const {
  const auto faceOk = [&](int32_t f) { return f >= 0 && f < topology_.numFaces; };
  const auto vertexOk = [&](int32_t v) {
    return v >= 0 && v < topology_.numVertices && topology_.vertexFaceCount[v] > 0;
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
        throw InputError("source/sink: vertex " + std::to_string(s.element) + " does not exist or is unused");
      break;
    case ConstraintKind::Edge:
      requireMagnitude(s.value, "edge value");
      if (s.edge[0] == s.edge[1])
        throw InputError("edge constraint: an edge needs two different vertices (got " +
                         std::to_string(s.edge[0]) + " twice)");
      if (findEdge(topology_, s.edge[0], s.edge[1]) < 0)
        throw InputError("edge constraint: vertices " + std::to_string(s.edge[0]) + " and " +
                         std::to_string(s.edge[1]) + " are not joined by an edge");
      break;
    case ConstraintKind::Stroke:
      break;  // strokeRows validates its points
    case ConstraintKind::Singularity:
      if (!vertexOk(s.element))
        throw InputError("singularity: vertex " + std::to_string(s.element) + " does not exist or is unused");
      requireFinite(s.value, "singularity index");
      break;  // the index's relation to N and the vertex's neighbours: design/prescribed_field_system.h
  }
}

std::vector<EdgeRow> ConstraintSet::rowsFor(const ConstraintSpec& s) const {
  switch (s.kind) {
    case ConstraintKind::Stroke:
      return strokeRows(mesh_, topology_, s.points);
    case ConstraintKind::Vector: {
      const Eigen::Vector3d u(s.vector[0], s.vector[1], s.vector[2]);
      return vectorRows(mesh_, topology_, s.element, u);
    }
    case ConstraintKind::Edge: {
      const int32_t e = findEdge(topology_, s.edge[0], s.edge[1]);
      return {{e, s.edge[0] < s.edge[1] ? s.value : -s.value}};
    }
    default:
      return {};
  }
}

int32_t ConstraintSet::add(ConstraintSpec spec) {
  validate(spec);
  const auto start = std::chrono::steady_clock::now();
  std::vector<EdgeRow> rows = rowsFor(spec);
  rowsMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  spec.id = nextId_++;
  if (isSingularKind(spec.kind)) singularStale_ = true;
  const int32_t id = spec.id;
  entries_.emplace(id, Entry{std::move(spec), std::move(rows)});
  return id;
}

double ConstraintSet::lastRowsMs() const {
  return rowsMs_;
}

const ConstraintSet::Entry& ConstraintSet::find(int32_t id) const {
  const auto it = entries_.find(id);
  if (it == entries_.end()) throw InputError("no constraint with id " + std::to_string(id));
  return it->second;
}

ConstraintSet::Entry& ConstraintSet::find(int32_t id) {
  return const_cast<Entry&>(std::as_const(*this).find(id));
}

void ConstraintSet::remove(int32_t id) {
  if (isSingularKind(find(id).spec.kind)) singularStale_ = true;
  entries_.erase(id);
}

const ConstraintSpec& ConstraintSet::spec(int32_t id) const {
  return find(id).spec;
}

void ConstraintSet::setElement(int32_t id, int32_t element) {
  Entry& e = find(id);
  ConstraintSpec moved = e.spec;
  moved.element = element;
  validate(moved);
  if (isEdgeKind(moved.kind)) e.rows = rowsFor(moved);
  if (isSingularKind(moved.kind)) singularStale_ = true;
  e.spec = std::move(moved);
}

double ConstraintSet::setWeight(int32_t id, double weight) {
  Entry& e = find(id);
  if (!isEdgeKind(e.spec.kind)) throw InputError("only strokes, vectors and edge constraints have a weight");
  requireWeight(weight);
  const double previous = e.spec.weight;
  e.spec.weight = weight;
  return previous;
}

void ConstraintSet::setStrength(int32_t id, double strength) {
  requireMagnitude(strength, "strength");
  Entry& e = find(id);
  e.spec.strength = strength;
  if (isSingularKind(e.spec.kind)) singularStale_ = true;
}

void ConstraintSet::clear() {
  entries_.clear();
  singularStale_ = true;
}

std::vector<ConstraintSpec> ConstraintSet::specs() const {
  std::vector<ConstraintSpec> out;
  for (const auto& [id, e] : entries_) out.push_back(e.spec);
  return out;
}

std::vector<ConstraintSpec> ConstraintSet::specsOf(ConstraintKind kind) const {
  std::vector<ConstraintSpec> out;
  for (const auto& [id, e] : entries_)
    if (e.spec.kind == kind) out.push_back(e.spec);
  return out;
}

void ConstraintSet::weightedRows(int32_t id, double weight, double scale, std::vector<int32_t>& rows,
                                 std::vector<double>& weights) const {
  for (const EdgeRow& r : find(id).rows) {
    rows.push_back(r.edge);
    weights.push_back(weight * scale);
  }
}

void ConstraintSet::allWeightedRows(double scale, std::vector<int32_t>& rows,
                                    std::vector<double>& weights) const {
  for (const auto& [id, e] : entries_)
    if (isEdgeKind(e.spec.kind))
      for (const EdgeRow& r : e.rows) {
        rows.push_back(r.edge);
        weights.push_back(e.spec.weight * scale);
      }
}

void ConstraintSet::operatorsChanged() {
  singularStale_ = true;
}

const Eigen::VectorXd& ConstraintSet::singularPart(const OneFormOperators& ops) {
  if (singularStale_ || singular_.size() != ops.d1.cols()) {
    const SourceTargets targets =
        singularTargets(topology_, geometry_, specsOf(ConstraintKind::Source), specsOf(ConstraintKind::Sink),
                        specsOf(ConstraintKind::Vortex));
    singular_ = ops.d1.transpose() * (geometry_.star2.asDiagonal() * targets.curl) +
                ops.divergence.transpose() * targets.divergence;
    singularStale_ = false;
  }
  return singular_;
}

Eigen::VectorXd ConstraintSet::rightHandSide(const OneFormOperators& ops, double scale) {
  Eigen::VectorXd b = singularPart(ops);
  for (const auto& [id, e] : entries_)
    if (isEdgeKind(e.spec.kind))
      for (const EdgeRow& r : e.rows) b[r.edge] += e.spec.weight * scale * e.spec.strength * r.value;
  return b;
}

std::vector<std::string> ConstraintSet::warnings(const BoundaryCondition& boundary) const {
  std::vector<std::string> out;
  if (boundary.free) return out;
  for (const auto& [id, e] : entries_)
    if ((e.spec.kind == ConstraintKind::Source || e.spec.kind == ConstraintKind::Sink) &&
        topology_.isBoundaryVertex[e.spec.element])
      out.push_back("constraint " + std::to_string(id) + ": a source or sink on boundary vertex " +
                    std::to_string(e.spec.element) + " has no effect under a fixed-angle boundary condition");
  return out;
}

}  // namespace tvf
