#pragma once
// Principal curvature directions per face as an N-power field, for aligning a line or cross field to
// curvature (Knöppel et al. 2013, Sec. 6): the shape operator of a face from the dihedral angles of its
// edges, S_f = sum_e (beta_e |e| / 2) t_e t_e' / A_f with t_e the in-plane normal of edge e, whose trace-free
// part in the face's frame is z = (kappa_1 - kappa_2) e^{2 i theta_1} (theta_1 the direction of larger
// curvature).
#include <complex>
#include <vector>

#include "dec/hodge_star.h"
#include "direction/levi_civita_connection.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// z^(N/2) with magnitude |z| (the anisotropy), scaled so the area-weighted mean of |q|^2 is 1. Even N only
// (InputError otherwise: curvature has 2-fold symmetry). All zero on a mesh without anisotropic curvature.
std::vector<std::complex<double>> principalCurvaturePower(const SurfaceMesh& mesh,
                                                          const MeshTopology& topology,
                                                          const MeshGeometry& geometry,
                                                          const FaceFrames& frames, int symmetry);

}  // namespace tvf
