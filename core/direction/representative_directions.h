#pragma once
// From a power field to what is drawn and written: one unit representative of the N directions per face (the
// others are it rotated by 2 pi k / N about the face normal) and per vertex.
#include <Eigen/Core>
#include <vector>

#include "dec/hodge_star.h"
#include "direction/levi_civita_connection.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// theta = arg(u_f) / N in f's frame, 3 per face; zero where u_f is exactly zero.
std::vector<double> faceRepresentatives(const FaceFrames& frames, const Eigen::VectorXd& power, int symmetry);

// At each vertex, the incident faces' directions projected into its tangent plane (area-weighted vertex
// normal), averaged as N-th powers, and one N-th root of the mean: unit, 3 per vertex, the choice among the N
// arbitrary (views match it to a neighbour before interpolating).
std::vector<double> vertexRepresentatives(const SurfaceMesh& mesh, const MeshTopology& topology,
                                          const MeshGeometry& geometry,
                                          const std::vector<double>& faceDirections, int symmetry);

// Each vertex's tangent plane (the area-weighted vertex normal's) and two axes in it: the mesh's alone, made
// once for every field's vertex representatives.
struct VertexTangentAxes {
  std::vector<double> a, b;  // 3 per vertex each, orthonormal, b = n x a
};
VertexTangentAxes vertexTangentAxes(const std::vector<double>& vertexNormals);
// The same representatives with the axes made beforehand (into out, reusing its room).
void vertexRepresentatives(const VertexTangentAxes& axes, const SurfaceMesh& mesh,
                           const MeshTopology& topology, const MeshGeometry& geometry,
                           const std::vector<double>& faceDirections, int symmetry, std::vector<double>& out);

// Two representatives a and b point the same way up to a rotation by 2 pi k / N: the angle between them
// reduced to (-pi/N, pi/N] (about `normal`).
double symmetricAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& normal,
                      int symmetry);

}  // namespace tvf
