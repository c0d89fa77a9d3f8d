#pragma once
// What a stroke or a direction constraint asks of an N-direction field: at each face it constrains, a unit
// power value q = e^{i N theta} (theta the wanted direction in the face's frame), entering the least-squares
// energy as w |u_f - q|^2 — two diagonal entries of the face's 2x2 block, so a rank-2 update per face.
#include <complex>
#include <cstdint>
#include <vector>

#include "constraints/constraint_spec.h"
#include "direction/levi_civita_connection.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct FaceDirectionTerm {
  int32_t face;
  std::complex<double> power;  // |power| = 1
};

// A stroke constrains every face its walk (constraints/surface_walk.h) leaves to the walk's heading there,
// and the face where it ends to the last heading; a face crossed twice is constrained twice, so a zig-zag
// means a zig-zag. A vector constrains its face. Throws InputError for other kinds (sources, sinks and
// vortices are vector notions; an edge value is a 1-form's) and for a vector with no tangential part.
std::vector<FaceDirectionTerm> directionTerms(const SurfaceMesh& mesh, const MeshTopology& topology,
                                              const FaceFrames& frames, const ConstraintSpec& spec,
                                              int symmetry);

// A fixed-angle boundary condition (dec/boundary_condition.h: beta per boundary edge, NaN elsewhere) as
// directions at the boundary faces: the direction at angle beta + pi/2 from the boundary edge (traversed in
// its face's orientation), turning towards the interior — the direction a vector field's fixed-angle row
// leaves free (tangential, beta = pi/2: along the boundary; normal, beta = 0: across it). One term per
// boundary edge.
std::vector<FaceDirectionTerm> boundaryDirectionTerms(const SurfaceMesh& mesh, const MeshTopology& topology,
                                                      const FaceFrames& frames,
                                                      const std::vector<double>& angles, int symmetry);

// A unit tangent at face f raised to the N-th power in f's frame (0 for a vector normal to the face).
std::complex<double> directionPower(const FaceFrames& frames, int32_t face, const double vector[3],
                                    int symmetry);

}  // namespace tvf
