#include "constraints/edge_rows.h"

#include "common/input_error.h"
#include "constraints/surface_walk.h"
#include "mesh/mesh_geometry.h"

namespace tvf {

std::vector<EdgeRow> vectorRows(const SurfaceMesh& mesh, const MeshTopology& t, int32_t face,
                                const Eigen::Vector3d& u) {
  const Eigen::Vector3d tangent = projectToFace(mesh, face, u);
  std::vector<EdgeRow> rows;
  for (int c = 0; c < 3; ++c) {
    const int32_t e = t.edgeOf(face, c);
    rows.push_back({e, tangent.dot(edgeVector(mesh, t, e))});
  }
  return rows;
}

std::vector<EdgeRow> strokeRows(const SurfaceMesh& mesh, const MeshTopology& t,
                                const std::vector<SurfacePoint>& input) {
  const StrokeWalk walk = walkStroke(mesh, t, input);
  std::vector<EdgeRow> rows;
  for (const StrokeCrossing& c : walk.crossings)
    rows.push_back({c.edge, c.direction.dot(edgeVector(mesh, t, c.edge))});
  if (!rows.empty()) return rows;
  const std::vector<SurfacePoint>& points = walk.points;
  const Eigen::Vector3d chord =
      surfacePointPosition(mesh, points.back()) - surfacePointPosition(mesh, points.front());
  const Eigen::Vector3d tangent = projectToFace(mesh, points.front().face, chord);
  if (!(tangent.norm() > 0)) throw InputError("the stroke has zero length");
  return vectorRows(mesh, t, points.front().face, tangent.normalized());
}

}  // namespace tvf
