#pragma once
// Index of the per-face field around each interior vertex: the turning of the field across the one-ring
// measured against discrete Levi-Civita transport (angles to shared edges), plus the angle defect.
#include <cstdint>
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct Singularity {
  int32_t vertex;
  double index;
  // The design prescribes this index at this vertex (design/designer.h: addSingularity); false for a
  // singularity the field placed itself.
  bool prescribed = false;
};

// Nonzero indices only. Vertices on a boundary, and vertices where the field vanishes in an incident face,
// have no index and are skipped. For an N-direction field (symmetry N > 1, faceVectors one representative per
// face) the turning between neighbours is taken modulo 2 pi / N, to the nearest of the N directions, so indices
// are multiples of 1/N.
std::vector<Singularity> findSingularities(const SurfaceMesh& mesh, const MeshTopology& topology,
                                           const MeshGeometry& geometry, const std::vector<double>& faceVectors,
                                           int symmetry = 1);

}  // namespace tvf
