#pragma once
// A closed genus-0 mesh of known shape, made in code: the wasm warm-up designs on it and the native tests
// measure against it.
#include "mesh/surface_mesh.h"

namespace tvf {

// The icosahedron with `subdivisions` midpoint subdivisions, projected to the unit sphere: 10 * 4^s + 2
// vertices, 30 * 4^s edges.
SurfaceMesh icosphere(int subdivisions);

}  // namespace tvf
