#pragma once
// The geometry of single vertices, edges and faces over the flat position array: the one place every module
// (Hodge stars, checks, constraints, reconstruction, exports, atlas) takes its normals, areas and barycentric
// gradients from, so that they all agree on a face to the last bit.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

inline Eigen::Vector3d vertexPosition(const SurfaceMesh& mesh, int32_t v) {
  return {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
}

inline void facePositions(const SurfaceMesh& mesh, int32_t f, Eigen::Vector3d p[3]) {
  for (int c = 0; c < 3; ++c) p[c] = vertexPosition(mesh, mesh.triangles[3 * f + c]);
}

// p_e in the edge's canonical orientation (lower vertex index to higher).
inline Eigen::Vector3d edgeVector(const SurfaceMesh& mesh, const MeshTopology& t, int32_t e) {
  return vertexPosition(mesh, t.edgeVertices[2 * e + 1]) - vertexPosition(mesh, t.edgeVertices[2 * e]);
}

// p_01 x p_02: right-handed with the face's winding and 2|t| long. Normals and areas all derive from this one
// product.
inline Eigen::Vector3d twiceAreaNormal(const Eigen::Vector3d p[3]) {
  return (p[1] - p[0]).cross(p[2] - p[0]);
}

struct FaceNormalArea {
  Eigen::Vector3d normal;  // unit; zero on a face of zero area, which the atlas keeps but cannot orient
  double area;
};

inline FaceNormalArea faceNormalArea(const Eigen::Vector3d p[3]) {
  const Eigen::Vector3d n = twiceAreaNormal(p);
  const double twiceArea = n.norm();
  return {twiceArea > 0 ? Eigen::Vector3d(n / twiceArea) : Eigen::Vector3d::Zero(), 0.5 * twiceArea};
}

inline Eigen::Vector3d faceNormal(const SurfaceMesh& mesh, int32_t f) {
  Eigen::Vector3d p[3];
  facePositions(mesh, f, p);
  return faceNormalArea(p).normal;
}

// grad(lambda_k) = n x p_{k+1,k+2} / 2|t|: constant over the face, so one set serves the stroke walk's exit
// test and Whitney reconstruction (Eq. 4 is sum_k w_k grad(lambda_k)) alike.
inline void barycentricGradients(const Eigen::Vector3d p[3], Eigen::Vector3d grad[3]) {
  const FaceNormalArea face = faceNormalArea(p);
  for (int k = 0; k < 3; ++k) grad[k] = face.normal.cross(p[(k + 2) % 3] - p[(k + 1) % 3]) / (2 * face.area);
}

// cot of the angle between u and v.
inline double cotan(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return u.dot(v) / u.cross(v).norm();
}

// Unit vertex normals, 3 per vertex: face normals weighted by face area (0 for vertices no face uses).
std::vector<double> vertexNormals(const SurfaceMesh& mesh);

}  // namespace tvf
