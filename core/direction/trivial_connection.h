#pragma once
// A trivial connection (Crane, Desbrun, Schroder 2010): the Levi-Civita connection between faces
// (direction/levi_civita_connection.h) changed by the smallest rotations x (one per interior edge, in the
// norm sum w x^2 of the field's own smoothness weights) such that its holonomy around each interior vertex
// leaves the index the design prescribes there and is a multiple of 2 pi / N around every other dual cycle
// (direction/dual_cycles.h): a field parallel for it exists and has exactly the prescribed singularities. The
// rotations are x = W^-1 C' lambda with (C W^-1 C') lambda = b, C the cycles' incidence; the vertex block of
// C W^-1 C' is a vertex Laplacian with weights 1/w, factored once per mesh (CHOLMOD), and the few handle and
// boundary-loop cycles enter through its Schur complement, so that each edit of the singularities is one
// solve with that factor. A handle's holonomy is rounded to the multiple of 2 pi / N nearest to what the
// vertex cycles alone leave it: the smoothest choice, handle by handle.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "common/sparse_matrix.h"
#include "direction/dual_cycles.h"
#include "direction/levi_civita_connection.h"
#include "solver/shifted_factor.h"

namespace tvf {

// What each vertex cycle's rotations must add up to: 2 pi k_v - K_v at a vertex with index k_v (K_v its angle
// defect), -K_v elsewhere.
std::vector<double> holonomyTargets(const MeshTopology& topology, const MeshGeometry& geometry,
                                    const std::map<int32_t, double>& indices);

// Whether the prescribed indices account for all the index the surface needs: on every closed component
// they sum to its Euler characteristic (a component with a boundary takes any sum).
bool indicesComplete(const MeshTopology& topology, const std::map<int32_t, double>& prescribed);

class TrivialConnection {
 public:
  // The topology and connection must outlive it.
  TrivialConnection(const MeshTopology& topology, const FaceConnection& connection);

  // The rotations x (one per connection entry) for these vertex targets (holonomyTargets) and symmetry N.
  std::vector<double> rotations(const std::vector<double>& vertexTargets, int symmetry);
  // A direction angle per face (in its frame) parallel for the changed connection angle + x, integrated
  // along the dual spanning tree from 0 at each component's first face.
  std::vector<double> parallelAngles(const std::vector<double>& rotations) const;
  // The largest |angle + x - (theta_f - theta_g)| over every entry, modulo 2 pi / N: 0 up to round-off when
  // theta is parallel for the changed connection.
  double parallelResidual(const std::vector<double>& rotations, const std::vector<double>& angles,
                          int symmetry) const;
  const DualCycles& cycles() const { return cycles_; }
  double lastSolveMs() const { return solveMs_; }

 private:
  void factorVertexBlock();

  const MeshTopology& topology_;
  const FaceConnection& connection_;
  DualCycles cycles_;
  std::vector<double> inverseWeight_;
  SparseMatrix vertexBlock_;  // upper triangle
  double scale_ = 1;          // its mean diagonal
  ShiftedFactor factor_;
  bool factored_ = false;
  SparseMatrix coupling_;           // B = C_V W^-1 C_G', vertex rows x generators
  Eigen::MatrixXd solvedCoupling_;  // Z = S_V^-1 B
  Eigen::MatrixXd schur_;           // S_G - B' Z
  double solveMs_ = 0;
};

}  // namespace tvf
