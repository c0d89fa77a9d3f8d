#pragma once
// An N-direction field designed by weighted least squares on its power field (Knöppel et al. 2013):
// (H + sum_k w_k E_k) u = sum_k w_k E_k q_k + s M q_curvature, with H the connection Laplacian
// (direction/connection_laplacian.h), E_k the two diagonal entries of a constrained face, q_k its unit power
// value and M the area mass. H is factored once (solver/shifted_factor.h: the kernel of a flat or torus-like
// mesh gets the same shift as the 1-form system's); a constraint enters and leaves as one multi-column rank
// update of that factor (a stroke over m faces: 2m columns), never a refactorization. With no constraint and
// no curvature alignment the field is the smoothest one: the lowest eigenvector of H u = lambda M u, by
// inverse iteration with the same factor.
#include <Eigen/Core>
#include <complex>
#include <cstdint>
#include <map>
#include <vector>

#include "common/sparse_matrix.h"
#include "dec/hodge_star.h"
#include "direction/direction_constraints.h"
#include "direction/levi_civita_connection.h"
#include "solver/shifted_factor.h"

namespace tvf {

struct PowerFieldReport {
  int32_t inverseIterations = 0;  // of the last solve (0: a constrained or curvature-aligned solve)
  double eigenvalue = 0;          // its Rayleigh quotient u'Hu / u'Mu (the smoothest field's energy)
};

class PowerFieldSystem {
 public:
  // The mesh, topology, geometry, the face frames and the Levi-Civita connection between them
  // (direction/levi_civita_connection.h) must outlive the system.
  PowerFieldSystem(const SurfaceMesh& mesh, const MeshTopology& topology, const MeshGeometry& geometry,
                   const FaceFrames& frames, const FaceConnection& connection, int symmetry);

  int symmetry() const;
  const FaceFrames& frames() const;
  ShiftedFactor& factor();
  // s >= 0: how strongly the field is pulled towards the principal curvature directions (0: not at all).
  void setCurvatureAlignment(double s);

  // Rotations added to the Levi-Civita connection's angles (one per entry, FaceConnection order; empty:
  // none): a trivial connection's (direction/trivial_connection.h). H changes, so the factor is made again
  // (its ordering kept: the pattern is the same).
  void setConnectionRotations(const std::vector<double>& rotations);

  // Directions the boundary condition fixes (direction/direction_constraints.h), at relative weight `weight`:
  // part of the base matrix (they change only with the boundary condition), so the factor is made again.
  void setBoundaryTerms(std::vector<FaceDirectionTerm> terms, double weight);

  // A constraint's face terms at its relative weight; ids as the Designer gives them.
  void add(int32_t id, std::vector<FaceDirectionTerm> terms, double weight);
  void remove(int32_t id);
  void setWeight(int32_t id, double weight);
  void clear();
  double lastUpdateMs() const;

  // Factors H + the boundary and constraint terms (what solve() does first when the factor is not current).
  void factorNow();
  // Solves (factoring first when needed); the power field u, 2 values (re, im) per face.
  void solve(Eigen::VectorXd& u);
  const PowerFieldReport& report() const;
  // The system the design means (H + constraint terms) and its right-hand side, for independent checks.
  void assemble(SparseMatrix& A, Eigen::VectorXd& b);
  SparseMatrix baseMatrix() const;  // H + the boundary terms, full
  double scale() const;             // relative weights are multiplied by this (H's mean diagonal)
  double nonZerosPerRow() const;    // of the base matrix

 private:
  struct Entry {
    std::vector<FaceDirectionTerm> terms;
    double weight;
  };
  DiagonalTerms termsOf(const Entry& entry, double weight) const;
  DiagonalTerms allTerms() const;
  Eigen::VectorXd rightHandSide();
  void smoothestField(Eigen::VectorXd& u);

  const SurfaceMesh& mesh_;
  const MeshTopology& topology_;
  const MeshGeometry& geometry_;
  int symmetry_;
  const FaceFrames& frames_;
  SparseMatrix connection_;  // H alone
  SparseMatrix base_;        // H + the boundary terms, upper triangle
  std::vector<FaceDirectionTerm> boundaryTerms_;
  double boundaryWeight_ = 0;
  Eigen::VectorXd mass_;
  double scale_ = 1;
  double curvatureAlignment_ = 0;
  std::vector<std::complex<double>> curvature_;  // computed on first use
  std::map<int32_t, Entry> entries_;
  ShiftedFactor factor_;
  PowerFieldReport report_;
};

}  // namespace tvf
