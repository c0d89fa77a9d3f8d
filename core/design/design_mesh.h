#pragma once
// The mesh a design is made on and what is derived from it alone, computed once and shared by the field
// systems, the read-outs and the exports: topology and geometry at construction, the Whitney maps and the
// fingerprint on first use. Nothing here depends on a field or a constraint.
#include <cstdint>
#include <optional>
#include <vector>

#include "dec/hodge_star.h"
#include "direction/levi_civita_connection.h"
#include "direction/representative_directions.h"
#include "field/whitney_reconstruction.h"
#include "mesh/feature_edges.h"
#include "mesh/mesh_checks.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

class DesignMesh {
 public:
  // A mesh that checkMesh() found usable, with the topology that check built.
  DesignMesh(SurfaceMesh mesh, MeshTopology topology);

  const SurfaceMesh& mesh() const { return mesh_; }
  const MeshTopology& topology() const { return topology_; }
  const MeshGeometry& geometry() const { return geometry_; }
  // The Whitney maps of Eq. 4 and 5 (geometry only), built on first use.
  const FaceVectorMap& faceVectorMap() const;
  const VertexVectorMap& vertexVectorMap() const;
  // Unit area-weighted vertex normals (mesh/mesh_geometry.h), and each vertex's tangent axes in the plane
  // they give (direction/representative_directions.h), built on first use: the vertex representatives, the
  // stripes' families and their combing read these.
  const std::vector<double>& vertexNormals() const;
  const VertexTangentAxes& vertexTangentAxes() const;
  // Each face's tangent frame and the discrete Levi-Civita connection between faces
  // (direction/levi_civita_connection.h), built on first use: every direction-field system reads these.
  const FaceFrames& faceFrames() const;
  const FaceConnection& leviCivitaConnection() const;
  uint64_t hash() const;  // meshHash(mesh()), made on first use
  // How its edges fold (mesh/feature_edges.h): the feature angle a new design starts at. Made on first use.
  const FoldProfile& foldProfile() const;

 private:
  SurfaceMesh mesh_;
  MeshTopology topology_;
  MeshGeometry geometry_;
  mutable FaceVectorMap faceVectorMap_;
  mutable VertexVectorMap vertexVectorMap_;
  mutable std::vector<double> vertexNormals_;
  mutable VertexTangentAxes vertexTangentAxes_;
  mutable std::optional<FaceFrames> faceFrames_;
  mutable std::optional<FaceConnection> leviCivitaConnection_;
  mutable std::optional<uint64_t> hash_;
  mutable std::optional<FoldProfile> foldProfile_;
};

}  // namespace tvf
