#pragma once
// A stroke's path over the surface: between consecutive points, the discrete straight line that leaves each
// face towards the next point re-projected into that face. Edge rows (1-forms) and face directions (N-fields)
// both read their constraints off the same crossings, so a stroke means the same path for every symmetry.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "constraints/constraint_spec.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct StrokeCrossing {
  int32_t face;               // the face the walk leaves
  int32_t edge;               // across this edge
  Eigen::Vector3d direction;  // unit heading in the face's plane
};

struct StrokeWalk {
  std::vector<SurfacePoint> points;  // validated, barycentric coordinates clamped and normalised
  std::vector<StrokeCrossing> crossings;
};

// Throws InputError naming the first bad point (a face that does not exist, coordinates out of range), or
// when there are fewer than two points. A segment that hits the boundary ends there.
StrokeWalk walkStroke(const SurfaceMesh& mesh, const MeshTopology& topology,
                      const std::vector<SurfacePoint>& points);

Eigen::Vector3d surfacePointPosition(const SurfaceMesh& mesh, const SurfacePoint& point);
Eigen::Vector3d projectToFace(const SurfaceMesh& mesh, int32_t face, const Eigen::Vector3d& u);

}  // namespace tvf
