#pragma once
// The vector field's system (the paper's Eq. 6): the DEC 1-form Laplacian M (curl^2 + div^2, or with gamma
// the bi-Laplacian) under the boundary condition, plus the weighted constraint rows Z'WZ of strokes, vectors
// and edge values, with sources, sinks and vortices in the right-hand side. One unknown per edge; the field
// is reconstructed by the Whitney maps (Eq. 4, 5).
#include "dec/one_form_laplacian.h"
#include "design/field_system.h"

namespace tvf {

class OneFormSystem final : public FieldSystem {
 public:
  OneFormSystem(const DesignMesh& mesh, ConstraintSet& constraints, const FieldSettings& settings);

  int symmetry() const override { return 1; }
  ShiftedFactor& factor() override { return factor_; }
  int64_t unknowns() const override;

  void setBoundary(const BoundaryCondition& bc) override;
  void setGamma(double gamma) override;
  void setCurvatureAlignment(double) override {}  // a direction-field notion
  // The faces beside each feature curve take the unit vector along it (oriented as the curve runs) as
  // strongly weighted rows of the base (a vector constraint's three edge rows), like a fixed boundary's.
  void setFeatures(const std::vector<int32_t>& edges) override;
  void resume() override;
  void releaseMemory() override;
  void prepareBase() override { requireBase(); }

  int32_t add(const ConstraintSpec& spec, DesignStats& stats) override;
  void remove(const ConstraintSpec& spec, DesignStats& stats) override;
  void reweight(const ConstraintSpec& spec, double previousWeight, DesignStats& stats) override;
  void clear(DesignStats& stats) override;

  void factorNow(DesignStats& stats) override;
  void solve(FieldSolution& field, DesignStats& stats) override;
  void vertexVectors(const FieldSolution& field, std::vector<double>& out) const override;

  void assemble(SparseMatrix& A, Eigen::VectorXd& b) override;
  SparseMatrix baseMatrix() override;
  double weightScale() override;

 private:
  void rebuildBase();
  void requireBase();
  DiagonalTerms constraintTerms() const;
  Eigen::VectorXd rightHandSide();
  // Constraint id's rows at relative weight `weight` into (or with downdate, out of) the factor.
  void updateRows(int32_t id, double weight, bool downdate, DesignStats& stats);

  const DesignMesh& mesh_;
  ConstraintSet& constraints_;
  BoundaryCondition boundary_;
  double gamma_ = 0;
  // The base system, rebuilt when the boundary condition or gamma change; its upper triangle only.
  bool baseStale_ = true;
  OneFormOperators ops_;
  SparseMatrix base_;
  double scale_ = 1;
  double nnzPerRowM_ = 0;
  std::vector<int32_t> featureEdges_;
  std::vector<double> featureValues_;
  ShiftedFactor factor_;
  // The next solve's face vectors, swapped in once known finite; between solves the previous field's, which
  // the vertex vectors' threads take for their partial sums.
  mutable std::vector<double> faceScratch_;
};

}  // namespace tvf
