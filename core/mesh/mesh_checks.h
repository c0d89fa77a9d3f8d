#pragma once
// Everything that makes a mesh unusable for 1-form design, found up front and named with its first offender.
#include <optional>
#include <string>
#include <vector>

#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct MeshProblem {
  std::string message;
  bool fatal;  // the mesh cannot be designed on; otherwise a note (e.g. unused vertices, which are ignored)
};

struct MeshReport {
  std::vector<MeshProblem> problems;
  std::optional<MeshTopology> topology;  // absent when indices are out of range or there are no faces

  bool usable() const;
  std::string firstFatal() const;  // empty when usable
};

MeshReport checkMesh(const SurfaceMesh& mesh);

}  // namespace tvf
