#pragma once
// A 64-bit hash of a mesh's geometry and connectivity: what a design file's "mesh" fingerprint names, so that
// a design made for another mesh is refused (design/design_document.h).
#include <cstdint>

#include "mesh/surface_mesh.h"

namespace tvf {

// FNV-1a over 32-bit words: the positions rounded to float (a design survives a float round trip of its
// mesh, as through glTF), then the triangles' indices.
uint64_t meshHash(const SurfaceMesh& mesh);

}  // namespace tvf
