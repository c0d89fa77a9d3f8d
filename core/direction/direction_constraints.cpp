#include "direction/direction_constraints.h"

#include <cmath>
#include <string>

#include "common/input_error.h"
#include "constraints/surface_walk.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

const char* kindName(ConstraintKind kind) {
  switch (kind) {
    case ConstraintKind::Source:
      return "a source";
    case ConstraintKind::Sink:
      return "a sink";
    case ConstraintKind::Vortex:
      return "a vortex";
    case ConstraintKind::Edge:
      return "an edge value";
    default:
      return "this constraint";
  }
}

void push(std::vector<FaceDirectionTerm>& terms, const FaceFrames& frames, int32_t face,
          const Eigen::Vector3d& direction, int symmetry) {
  const std::complex<double> q = directionPower(frames, face, direction.data(), symmetry);
  if (std::abs(q) > 0) terms.push_back({face, q});
}

}  // namespace

std::complex<double> directionPower(const FaceFrames& frames, int32_t face, const double vector[3],
                                    int symmetry) {
  const std::complex<double> z = inFaceFrame(frames, face, vector);
  const double r = std::abs(z);
  if (!(r > 0) || !std::isfinite(r)) return 0;
  return std::polar(1.0, symmetry * std::arg(z));
}

std::vector<FaceDirectionTerm> boundaryDirectionTerms(const SurfaceMesh& mesh, const MeshTopology& t,
                                                      const FaceFrames& frames,
                                                      const std::vector<double>& angles, int symmetry) {
  std::vector<FaceDirectionTerm> terms;
  if (angles.empty()) return terms;
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int c = 0; c < 3; ++c) {
      const int32_t e = t.edgeOf(f, c);
      if (!t.isBoundaryEdge[e]) continue;
      Eigen::Vector3d p[3];
      facePositions(mesh, f, p);
      const Eigen::Vector3d along = (p[(c + 1) % 3] - p[c]).normalized();
      const Eigen::Vector3d inward = faceNormalArea(p).normal.cross(along);
      const double beta = angles[e];
      push(terms, frames, f, -std::sin(beta) * along + std::cos(beta) * inward, symmetry);
    }
  return terms;
}

std::vector<FaceDirectionTerm> directionTerms(const SurfaceMesh& mesh, const MeshTopology& t,
                                              const FaceFrames& frames, const ConstraintSpec& spec,
                                              int symmetry) {
  std::vector<FaceDirectionTerm> terms;
  if (spec.kind == ConstraintKind::Vector) {
    push(terms, frames, spec.element, projectToFace(mesh, spec.element, Eigen::Vector3d(spec.vector)),
         symmetry);
    if (terms.empty())
      throw InputError("the vector at face " + std::to_string(spec.element) +
                       " has no direction in the face's plane");
    return terms;
  }
  if (spec.kind != ConstraintKind::Stroke)
    throw InputError(std::string(kindName(spec.kind)) + " is a vector-field notion: a field of symmetry " +
                     std::to_string(symmetry) + " takes strokes and directions only");
  const StrokeWalk walk = walkStroke(mesh, t, spec.points);
  for (const StrokeCrossing& c : walk.crossings) push(terms, frames, c.face, c.direction, symmetry);
  if (!walk.crossings.empty()) {
    // The last face entered keeps the heading it was entered with (re-projected into its plane).
    const StrokeCrossing& last = walk.crossings.back();
    const int32_t end = t.otherFace(last.edge, last.face);
    if (end >= 0) push(terms, frames, end, projectToFace(mesh, end, last.direction), symmetry);
    return terms;
  }
  const Eigen::Vector3d chord =
      surfacePointPosition(mesh, walk.points.back()) - surfacePointPosition(mesh, walk.points.front());
  push(terms, frames, walk.points.front().face, projectToFace(mesh, walk.points.front().face, chord),
       symmetry);
  if (terms.empty()) throw InputError("the stroke has zero length");
  return terms;
}

}  // namespace tvf
