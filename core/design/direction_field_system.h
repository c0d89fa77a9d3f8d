#pragma once
// The N-direction field's system (N = 2..6: line, cross and other symmetric fields) as a design's field
// system: the power-field system (direction/power_field_system.h) fed with the design's strokes and
// vectors as face terms (direction/direction_constraints.h), a fixed-angle boundary as strongly weighted
// face terms, and read out as unit representatives of the N directions per face and per vertex.
#include <memory>
#include <string>
#include <vector>

#include "design/field_system.h"
#include "direction/power_field_system.h"

namespace tvf {

// Throws InputError when `specs` hold sources, sinks, vortices or edge values, naming how many of each and
// `field` (e.g. "a field of symmetry 4") as what cannot take them.
void refuseVectorNotions(const std::vector<ConstraintSpec>& specs, const std::string& field);

// What a direction field's base holds besides its smoothness: a fixed-angle boundary as directions at the
// boundary faces (none for a free one) and the faces beside the feature edges along them
// (direction/feature_terms.h), both taken at kBoundaryWeight.
std::vector<FaceDirectionTerm> fixedDirectionTerms(const DesignMesh& mesh, const BoundaryCondition& boundary,
                                                   const std::vector<int32_t>& featureEdges, int symmetry);

class DirectionFieldSystem final : public FieldSystem {
 public:
  // Throws InputError when the design holds constraints an N-direction field cannot take (sources, sinks,
  // vortices, edge values), naming them.
  DirectionFieldSystem(int symmetry, const DesignMesh& mesh, ConstraintSet& constraints,
                       const FieldSettings& settings);

  int symmetry() const override { return symmetry_; }
  ShiftedFactor& factor() override { return system_.factor(); }
  int64_t unknowns() const override;

  void setBoundary(const BoundaryCondition& bc) override;
  void setGamma(double gamma) override { gamma_ = gamma; }  // a vector-field notion: only a warning here
  void setCurvatureAlignment(double s) override { system_.setCurvatureAlignment(s); }
  void setFeatures(const std::vector<int32_t>& edges) override;
  void resume() override;

  int32_t add(const ConstraintSpec& spec, DesignStats& stats) override;
  void remove(const ConstraintSpec& spec, DesignStats& stats) override;
  void reweight(const ConstraintSpec& spec, double previousWeight, DesignStats& stats) override;
  void clear(DesignStats& stats) override;

  void factorNow(DesignStats& stats) override;
  void solve(FieldSolution& field, DesignStats& stats) override;
  void vertexVectors(const FieldSolution& field, std::vector<double>& out) const override;

  void assemble(SparseMatrix& A, Eigen::VectorXd& b) override { system_.assemble(A, b); }
  SparseMatrix baseMatrix() override { return system_.baseMatrix(); }
  double weightScale() override { return system_.scale(); }

 private:
  void fixedTerms();  // the boundary's and the features' terms into the base
  void addAll();      // every stored constraint's terms (the factor is made with them at the next solve)

  int symmetry_;
  const DesignMesh& mesh_;
  ConstraintSet& constraints_;
  double gamma_;
  PowerFieldSystem system_;
  BoundaryCondition boundary_;
  std::vector<int32_t> featureEdges_;
};

}  // namespace tvf
