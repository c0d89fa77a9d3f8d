#pragma once
// Diagonal Hodge stars and the per-corner quantities they are built from.
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct MeshGeometry {
  std::vector<double> faceArea;    // |t|
  std::vector<double> cornerCot;   // 3 per face: cot of the angle at corner c (opposite edge c+1)
  std::vector<double> cornerArea;  // 3 per face: mixed Voronoi area of the face's corner (always > 0)
  Eigen::VectorXd star0;           // dual vertex area, strictly positive
  Eigen::VectorXd star1;           // (cot a + cot b)/2; may be zero or negative on obtuse meshes
  Eigen::VectorXd star2;           // 1/|t|
  Eigen::VectorXd whitneyMass1;    // diagonal of the Whitney 1-form mass matrix, strictly positive
  std::vector<double> faceNormal;  // 3 per face, unit
  std::vector<double>
      angleDefect;  // 2 pi - sum of corner angles, per vertex (meaningful on interior vertices)
  int32_t positiveAreaFallbackVertices = 0;  // vertices whose circumcentric area was not positive
  double totalArea = 0, meanEdgeLength = 0;
};

// star0 is the signed circumcentric area where it is positive and the mixed Voronoi area (Meyer et al. 2002)
// elsewhere: M is positive semidefinite exactly when star0 > 0, whatever the signs of star1.
MeshGeometry computeMeshGeometry(const SurfaceMesh& mesh, const MeshTopology& topology);

}  // namespace tvf
