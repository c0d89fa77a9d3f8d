#pragma once
// Where a field puts the index its design leaves unprescribed. A closed surface needs index chi in all; when
// the prescribed singularities sum to less or more, the rest goes where the smoothest field of the same
// design without them (its strokes, directions, boundary and features; direction/power_field_system.h) has
// its own singularities: each prescribed singularity takes the place of the nearest of those with an index of
// its sign, unit of 1/N by unit, so that placing a singularity pulls the nearest free one to it, and whatever
// a prescription cannot take from them (a -1/4 on a sphere whose smoothest cross field has only +1/4s) is
// given back by a singularity of the other sign at the vertex farthest from all the others. The prescribed
// and the free singularities together then sum to chi on every closed component, and the trivial connection
// of both (direction/trivial_connection.h) gives a field with exactly those singularities.
#include <cstdint>
#include <map>

#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// natural: the smoothest field's singularities (vertex -> index); prescribed: the design's. Returns the free
// singularities (none on a vertex that has a prescribed one), so that prescribed + free sum to the Euler
// characteristic on every closed component; components with a boundary get none.
std::map<int32_t, double> freeSingularities(const SurfaceMesh& mesh, const MeshTopology& topology,
                                            const std::map<int32_t, double>& natural,
                                            const std::map<int32_t, double>& prescribed, int symmetry);

}  // namespace tvf
