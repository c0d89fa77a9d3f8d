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

// Eq. 5 from the face map: each corner's Whitney vector is a combination of its face's barycentric
// gradients, which the face map's three vectors determine (they are differences of them, and the gradients
// sum to zero), weighted by the corner's area over its vertex's total. Per mesh only the totals are kept: a
// map of its own (6 doubles per edge) was 60 MB at 1.25M edges, and grew the wasm heap past its peak.
struct VertexVectorMap {
  int32_t numVertices = 0;
  std::vector<double> inverseArea;  // per vertex: 1 / the sum of its corner areas (0 where that is not > 0)
  bool empty() const { return inverseArea.empty() && numVertices == 0; }
};
VertexVectorMap vertexVectorMap(const SurfaceMesh& mesh, const MeshTopology& topology,
                                const MeshGeometry& geometry);
void vertexVectors(const VertexVectorMap& map, const FaceVectorMap& faces, const SurfaceMesh& mesh,
                   const MeshTopology& topology, const MeshGeometry& geometry, const double* oneForm,
                   std::vector<double>& out);
// The same, with the partial sums of its parts (two above 50k faces, on the solver's helper threads) in
// scratch (contents ignored; in one part, summed in face order, when it is too small): a caller with a spare
// array lends it, where a new one (10 MB at 416k vertices, made just after the factorization) would grow the
// wasm heap past its peak.
void vertexVectors(const VertexVectorMap& map, const FaceVectorMap& faces, const SurfaceMesh& mesh,
                   const MeshTopology& topology, const MeshGeometry& geometry, const double* oneForm,
                   std::vector<double>& out, std::vector<double>& scratch);
// Texture-domain vectors at barycentres (2 per face); empty when the mesh has no UVs.
void textureFaceVectors(const SurfaceMesh& mesh, const MeshTopology& topology, const double* oneForm,
                        std::vector<double>& out);

}  // namespace tvf
