#pragma once
// An N-direction field as an angle per face, theta = theta_parallel + phi: theta_parallel is parallel for a
// trivial connection (direction/trivial_connection.h) and phi a real function on faces, the field's turning
// away from it. Measured against the Levi-Civita connection the field turns by x_e + phi_f - phi_g across an
// edge (x the connection's rotations), so its smoothness energy is sum w (x + d phi)^2 = |x|^2 + |d phi|^2
// (x is orthogonal to every d phi: it is W^-1 C' lambda and cycles of d phi vanish), and strokes, directions
// and a fixed boundary pull phi by weighted least squares: (L + sum_k w_k e_k e_k') phi = sum_k w_k tau_k,
// with L the face graph Laplacian of those weights. L is factored once; a constraint is a rank update per
// face, never a refactorization; moving a singularity changes theta_parallel, the targets tau and nothing
// else. Because phi is a function, never an angle modulo 2 pi, the field's singularities are the connection's
// wherever it turns by less than pi / N across an edge: strokes can bend the field, never add or move them.
// A target direction is an angle modulo 2 pi / N: each stroke's targets are unwrapped along the stroke and
// the stroke as a whole, and each single target, take the branch nearest the field (iterated to a fixed
// point, a few solves with the same factor).
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "common/sparse_matrix.h"
#include "direction/direction_constraints.h"
#include "direction/levi_civita_connection.h"
#include "solver/shifted_factor.h"

namespace tvf {

class AngleFieldSystem {
 public:
  // The connection must outlive the system.
  AngleFieldSystem(const MeshTopology& topology, const FaceConnection& connection, int symmetry);

  ShiftedFactor& factor() { return factor_; }
  // Terms that belong to the base (a fixed boundary, features), each its own branch; refactors.
  void setFixedTerms(std::vector<FaceDirectionTerm> terms, double weight);
  // A constraint's terms in walking order (unwrapped together), at relative weight `weight`.
  void add(int32_t id, std::vector<FaceDirectionTerm> terms, double weight);
  void remove(int32_t id);
  void setWeight(int32_t id, double weight);
  void clear();
  double lastUpdateMs() const { return factor_.lastUpdateMs(); }

  // The field phi turns away from.
  void setParallel(std::vector<double> parallelAngles);
  void factorNow();
  // theta per face (angle in its frame).
  void solve(std::vector<double>& theta);
  void assemble(SparseMatrix& A, Eigen::VectorXd& b);
  SparseMatrix baseMatrix() const { return fullFromUpper(base_); }
  double scale() const { return scale_; }
  double nonZerosPerRow() const;
  int branchIterations() const { return iterations_; }

 private:
  struct Entry {
    std::vector<FaceDirectionTerm> terms;
    double weight;
  };
  DiagonalTerms termsOf(const std::vector<FaceDirectionTerm>& terms, double weight) const;
  DiagonalTerms allTerms() const;
  // The branch of each target nearest phi; a group's targets unwrapped along it first.
  void targets(const std::vector<FaceDirectionTerm>& terms, bool unwrap, std::vector<double>& out) const;
  Eigen::VectorXd rightHandSide(std::vector<double>& branches) const;

  const MeshTopology& topology_;
  int symmetry_;
  SparseMatrix laplacian_, base_;  // base_: upper triangle, with the fixed terms
  std::vector<FaceDirectionTerm> fixed_;
  double fixedWeight_ = 0;
  double scale_ = 1;
  std::map<int32_t, Entry> entries_;
  std::vector<double> parallel_;
  Eigen::VectorXd phi_;
  ShiftedFactor factor_;
  int iterations_ = 0;
};

}  // namespace tvf
