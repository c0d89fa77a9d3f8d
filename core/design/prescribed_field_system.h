#pragma once
// The field of a design with prescribed singularities, any symmetry N = 1..6 (N = 1: a unit vector field):
// the Levi-Civita connection made trivial except at the prescribed vertices (direction/trivial_connection.h).
// When the prescribed indices account for all the index the surface needs ("exact": they sum to the Euler
// characteristic on every closed component, or the component has a boundary to take the rest), the field is
// the trivial connection's parallel field turned by a function (direction/angle_field_system.h): it has
// exactly the prescribed singularities, strokes and directions bend it without adding any, and placing,
// moving or removing a singularity changes only right-hand sides (one vertex-Laplacian solve for the
// rotations, then the angle solve with its factor). Otherwise ("free") the rest of the index is left as
// curvature spread over the other vertices and the field is the power field (Knoppel et al. 2013) of the
// changed connection, which places that rest as singularities of its own; a change of the singularities then
// changes the connection, so the power field's factor is made again (its ordering kept).
#include <map>
#include <memory>

#include "design/field_system.h"
#include "direction/angle_field_system.h"
#include "direction/power_field_system.h"
#include "direction/trivial_connection.h"

namespace tvf {

// Throws InputError naming the problem when `spec` (a Singularity) cannot be prescribed on this mesh at
// symmetry N beside the set's others (ignoring the one with id `ignoreId`, the singularity being moved): an
// unused or boundary vertex, an index that is not a nonzero multiple of 1/N, a vertex that has one already,
// an index too large for the vertex's one-ring to show (an edge's share of the turning past 0.8 pi / N).
void checkSingularity(const ConstraintSpec& spec, int symmetry, const SurfaceMesh& mesh,
                      const MeshTopology& topology, const MeshGeometry& geometry,
                      const ConstraintSet& constraints, int32_t ignoreId = 0);

class PrescribedFieldSystem final : public FieldSystem {
 public:
  // Throws InputError naming what the design holds that it cannot take (sources, sinks, vortices, edge
  // values; an index that is not a multiple of 1/N).
  PrescribedFieldSystem(int symmetry, const DesignMesh& mesh, ConstraintSet& constraints,
                        const FieldSettings& settings);

  int symmetry() const override { return symmetry_; }
  ShiftedFactor& factor() override;
  int64_t unknowns() const override;
  bool prescribes() const override { return true; }

  void setBoundary(const BoundaryCondition& bc) override;
  void setGamma(double gamma) override { gamma_ = gamma; }
  void setCurvatureAlignment(double s) override;
  void setFeatures(const std::vector<int32_t>& edges) override;
  void resume() override;
  void singularitiesChanged() override { connectionStale_ = true; }

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

  // For checks: the trivial connection's rotations of the last solve and the parallel field's residual.
  const std::vector<double>& rotations() const { return rotations_; }
  const TrivialConnection& connection() const { return trivial_; }
  bool exact() const { return exact_; }

 private:
  std::map<int32_t, double> prescribed() const;
  void updateConnection(DesignStats& stats);
  void fixedTerms();
  void addAll();
  PowerFieldSystem& power();

  int symmetry_;
  const DesignMesh& mesh_;
  ConstraintSet& constraints_;
  FieldSettings settings_;
  double gamma_;
  FaceFrames frames_;
  FaceConnection leviCivita_;
  TrivialConnection trivial_;
  AngleFieldSystem angles_;
  std::unique_ptr<PowerFieldSystem> power_;  // the free case's, made on first need
  std::vector<FaceDirectionTerm> boundaryTerms_, featureTerms_;
  bool connectionStale_ = true;
  bool exact_ = true;
  std::vector<double> rotations_;
};

}  // namespace tvf
