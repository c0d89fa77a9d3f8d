#pragma once
// Vector fields from 1-forms with Whitney elements (Eq. 4, 5), on the surface and in the texture domain.
#include <Eigen/Core>
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// The field at barycentric point `bary` of `face`: 2|t| u = (c_ki a_k - c_ij a_j) p_jk^perp + ... (Eq. 4).
Eigen::Vector3d whitneyVector(const SurfaceMesh& mesh, const MeshTopology& topology, const double* oneForm,
                              int32_t face, const double bary[3]);

// Eq. 4 with UV positions and UV area: the field pushed into the texture domain (needs mesh.cornerUVs).
Eigen::Vector2d whitneyTextureVector(const SurfaceMesh& mesh, const MeshTopology& topology,
                                     const double* oneForm, int32_t face, const double bary[3]);

// Per-face vectors at barycentres (3 per face).
void faceVectors(const SurfaceMesh& mesh, const MeshTopology& topology, const double* oneForm,
                 std::vector<double>& out);

// The same as a linear map of the face's three 1-form values: 3 coefficient vectors per face (orientation
// signs included), built once per mesh, so that reconstructing after every solve does no geometry.
struct FaceVectorMap {
  std::vector<double> coefficient;  // 9 per face: the vector for edge k of face f at 9 f + 3 k
};
FaceVectorMap faceVectorMap(const SurfaceMesh& mesh, const MeshTopology& topology);
void faceVectors(const FaceVectorMap& map, const MeshTopology& topology, const double* oneForm,
                 std::vector<double>& out);
// Per-vertex vectors: the corner values of Eq. 4 averaged with mixed Voronoi corner areas (Eq. 5).
void vertexVectors(const SurfaceMesh& mesh, const MeshTopology& topology, const MeshGeometry& geometry,
                   const double* oneForm, std::vector<double>& out);

// Eq. 5 as the linear map it is: vertex v's vector is a sum over the edges at v of the edge's 1-form value
// times a 3-vector that depends on the geometry only. Built once per mesh, applying it reads each edge value
// once and does no geometry (the interactive loop derives vertex vectors after every edit). The edges' ends
// are the topology's, not copied (a map is 48 bytes per edge already).
struct VertexVectorMap {
  int32_t numVertices = 0;
  std::vector<double> coefficient;  // 6 per edge: the 3-vector for its first vertex, then for its second
  bool empty() const { return coefficient.empty() && numVertices == 0; }
};
VertexVectorMap vertexVectorMap(const SurfaceMesh& mesh, const MeshTopology& topology,
                                const MeshGeometry& geometry);
void vertexVectors(const VertexVectorMap& map, const MeshTopology& topology, const double* oneForm,
                   std::vector<double>& out);
// Texture-domain vectors at barycentres (2 per face); empty when the mesh has no UVs.
void textureFaceVectors(const SurfaceMesh& mesh, const MeshTopology& topology, const double* oneForm,
                        std::vector<double>& out);

}  // namespace tvf
