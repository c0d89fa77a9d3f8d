#pragma once
// The discrete Levi-Civita connection between adjacent faces (Knöppel, Crane, Pinkall, Schröder 2013): each
// face has a tangent frame (its first edge and the normal x it), and transport across a shared edge unfolds
// one face onto the other about that edge, which in the two frames is a rotation by the difference of the
// angles the edge makes in each. Angle defects enter through these rotations: around a vertex they sum to its
// defect.
#include <complex>
#include <cstdint>
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// e1 of each face (3 per face, unit): the direction of its corner-0-to-corner-1 edge; e2 = normal x e1.
struct FaceFrames {
  std::vector<double> e1, e2;
};
FaceFrames faceFrames(const SurfaceMesh& mesh, const MeshGeometry& geometry);

// A 3D tangent vector at face f as a complex number in f's frame, and back.
std::complex<double> inFaceFrame(const FaceFrames& frames, int32_t f, const double vector[3]);
void fromFaceFrame(const FaceFrames& frames, int32_t f, std::complex<double> z, double out[3]);

// Per interior edge: the faces f, g on either side, the rotation `angle` that carries a direction at g (in
// g's frame) to f's frame (theta_f = theta_g + angle), and a positive smoothness weight.
struct FaceConnection {
  std::vector<int32_t> faceF, faceG;
  std::vector<double> angle, weight;
};
// Weights |e|^2 / (2/3 (A_f + A_g)): the squared difference quotient of a face field across the edge (its
// barycentres are about 2/3 (A_f + A_g) / |e| apart) times the area it stands for. Unlike cotan weights they
// are positive on every mesh.
FaceConnection leviCivitaConnection(const SurfaceMesh& mesh, const MeshTopology& topology,
                                    const MeshGeometry& geometry, const FaceFrames& frames);

}  // namespace tvf
