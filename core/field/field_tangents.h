#pragma once
// Tangent frames from a designed field: the per-vertex field (Eq. 5) projected into each vertex's tangent
// plane and normalized, as glTF's TANGENT attribute wants it.
#include <vector>

#include "mesh/surface_mesh.h"

namespace tvf {

// 3 per vertex, unit and orthogonal to `normals` (mesh/mesh_geometry.h's vertexNormals). Where the projected
// field vanishes (below 1e-9 of the largest), the direction of the vertex's first edge stands in, so every
// tangent is a valid unit vector.
std::vector<double> fieldTangents(const SurfaceMesh& mesh, const std::vector<double>& normals,
                                  const std::vector<double>& vertexField);

}  // namespace tvf
