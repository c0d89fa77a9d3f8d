#pragma once
// The field of a design with prescribed singularities, any symmetry N = 1..6 (N = 1: a unit vector field):
// the parallel field of a trivial connection (direction/trivial_connection.h) turned by a function
// (direction/angle_field_system.h), so that it has exactly the singularities the connection was made for, and
// strokes, directions, a fixed boundary and features bend it without adding, moving or cancelling any. When
// the prescribed indices account for all the index the surface needs ("exact": they sum to the Euler
// characteristic on every closed component, or the component has a boundary to take the rest) those are all
// its singularities. Otherwise ("free") the rest goes where the smoothest field of the same design without
// the prescriptions puts its own (direction/free_singularities.h): that power field (Knoppel et al. 2013) is
// kept factored beside the angle system and solved again only when a stroke, direction, the boundary or a
// feature changes. Placing, moving or removing a singularity changes right-hand sides only: one solve with
// the connection's vertex-Laplacian factor and one with the angle system's, never a factorization.
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

// Throws InputError when `vertex` lies inside a sharp feature curve (exactly two of featureEdges meet there):
// the field is held along the curve on both sides, so no index can show there.
void checkOffFeatureCurves(int32_t vertex, const MeshTopology& topology,
                           const std::vector<int32_t>& featureEdges);

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
  void seedSmoothestSingularities(std::map<int32_t, double> singularities) override;

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

  bool exact() const { return exact_; }
  const std::map<int32_t, double>& freeSingularities() const { return free_; }  // of the last solve

 private:
  std::map<int32_t, double> prescribed() const;
  void updateConnection(DesignStats& stats);
  void fixedTerms();
  void addAll();
  PowerFieldSystem& power();
  void naturalChanged();
  void warnUnseen(const FieldSolution& field, DesignStats& stats)
      const;  // a stroke, direction, boundary or feature changed the smoothest field
  const std::map<int32_t, double>& natural();

  int symmetry_;
  const DesignMesh& mesh_;
  ConstraintSet& constraints_;
  FieldSettings settings_;
  double gamma_;
  const FaceFrames& frames_;  // the mesh's (design/design_mesh.h)
  TrivialConnection trivial_;
  AngleFieldSystem angles_;
  std::unique_ptr<PowerFieldSystem> power_;  // the smoothest field without prescriptions, made on first need
  std::map<int32_t, double> natural_, free_;
  bool naturalStale_ = true;
  bool connectionStale_ = true;
  bool exact_ = true;
  std::vector<double> rotations_;
};

}  // namespace tvf
