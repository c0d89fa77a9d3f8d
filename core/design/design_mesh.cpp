#include "design/design_mesh.h"

#include <utility>

#include "mesh/mesh_geometry.h"
#include "mesh/mesh_hash.h"

namespace tvf {

DesignMesh::DesignMesh(SurfaceMesh mesh, MeshTopology topology)
    : mesh_(std::move(mesh)),
      topology_(std::move(topology)),
      geometry_(computeMeshGeometry(mesh_, topology_)) {}

const FaceVectorMap& DesignMesh::faceVectorMap() const {
  if (faceVectorMap_.coefficient.empty()) faceVectorMap_ = tvf::faceVectorMap(mesh_, topology_);
  return faceVectorMap_;
}

const VertexVectorMap& DesignMesh::vertexVectorMap() const {
  if (vertexVectorMap_.empty()) vertexVectorMap_ = tvf::vertexVectorMap(mesh_, topology_, geometry_);
  return vertexVectorMap_;
}

const std::vector<double>& DesignMesh::vertexNormals() const {
  if (vertexNormals_.empty()) vertexNormals_ = tvf::vertexNormals(mesh_);
  return vertexNormals_;
}

const VertexTangentAxes& DesignMesh::vertexTangentAxes() const {
  if (vertexTangentAxes_.a.empty()) vertexTangentAxes_ = tvf::vertexTangentAxes(vertexNormals());
  return vertexTangentAxes_;
}

const FaceFrames& DesignMesh::faceFrames() const {
  if (!faceFrames_) faceFrames_ = tvf::faceFrames(mesh_, geometry_);
  return *faceFrames_;
}

const FaceConnection& DesignMesh::leviCivitaConnection() const {
  if (!leviCivitaConnection_)
    leviCivitaConnection_ = tvf::leviCivitaConnection(mesh_, topology_, geometry_, faceFrames());
  return *leviCivitaConnection_;
}

uint64_t DesignMesh::hash() const {
  if (!hash_) hash_ = meshHash(mesh_);
  return *hash_;
}

const FoldProfile& DesignMesh::foldProfile() const {
  if (!foldProfile_) foldProfile_ = tvf::foldProfile(mesh_, topology_, geometry_);
  return *foldProfile_;
}

}  // namespace tvf
