#pragma once
// One interface for the design's field systems, so that the Designer dispatches once and never asks which
// kind of field it holds: the vector field's 1-form system (design/one_form_system.h: the paper's M with
// constraint rows, sources, sinks and vortices) and the N-direction field's power-field system
// (design/direction_field_system.h: Knoppel et al. 2013's connection Laplacian with face terms). Each owns
// its base matrix and its ShiftedFactor: assembled once, factored once, every constraint edit a rank update
// of that factor (held beside it and solved through by the Woodbury identity while updates are deferred),
// read-outs made from its own unknowns.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "common/sparse_matrix.h"
#include "constraints/constraint_set.h"
#include "constraints/constraint_spec.h"
#include "dec/boundary_condition.h"
#include "design/design_mesh.h"
#include "design/design_stats.h"
#include "solver/shifted_factor.h"

namespace tvf {

// The field of one solve: its unknowns and the face vectors made from them (3 per face: the vector field's
// at the barycentre, or a unit representative of the N directions).
struct FieldSolution {
  int symmetry = 1;
  Eigen::VectorXd unknowns;         // a 1-form (one value per edge) or a power field (re, im per face)
  std::vector<double> oneForm;      // the vector field's unknowns as the read-outs hand them out; else empty
  std::vector<double> faceVectors;  // empty before the first solve
  std::map<int32_t, double> prescribed;  // the singularities the solve's design prescribed: vertex -> index
};

// What a system is made with and must follow: the design's base settings and how its factor runs.
struct FieldSettings {
  BoundaryCondition boundary;
  double gamma = 0;
  double curvatureAlignment = 0;
  FillOrdering ordering = FillOrdering::Metis;
  int threads = 0;  // 0: the factor's default
  double memoryLimit = 0;
  bool deferUpdates = false;
  std::vector<int32_t> featureEdges;  // mesh/feature_edges.h: the edges the field follows
  // The field has exactly the prescribed singularities, none when none are prescribed (a torus's field
  // without any): the prescribed-singularity system even for an empty set.
  bool exactSingularities = false;
};

// A fixed-angle boundary is enforced this strongly relative to the mean diagonal, in either system.
constexpr double kBoundaryWeight = 1e4;

class FieldSystem {
 public:
  virtual ~FieldSystem() = default;
  virtual int symmetry() const = 0;
  virtual ShiftedFactor& factor() = 0;
  // Rows of the system (edges, or two per face): what the factor's fill is measured against.
  virtual int64_t unknowns() const = 0;

  // Base changes: the factor is made again at the next solve.
  virtual void setBoundary(const BoundaryCondition& bc) = 0;
  virtual void setGamma(double gamma) = 0;
  virtual void setCurvatureAlignment(double s) = 0;
  // The edges whose direction the faces beside them take, strongly weighted (direction/feature_terms.h).
  virtual void setFeatures(const std::vector<int32_t>& edges) = 0;
  // Whether this system places the design's prescribed singularities (design/prescribed_field_system.h).
  virtual bool prescribes() const { return false; }
  // The design's singularities changed (added, moved or removed in the constraint set).
  virtual void singularitiesChanged() {}
  // The singularities of the smoothest field of the design as it now is without prescriptions (the field the
  // system in use before this one solved last, unedited since), so that it need not be solved again.
  virtual void seedSmoothestSingularities(std::map<int32_t, double>) {}
  // Lets the factor go, and what it is made from where that is large (a model being replaced: its memory is
  // where the next model's will go, solver/factor_memory.h); the next solve makes them again.
  virtual void releaseMemory() { factor().release(); }
  // The base matrix made now where it is made lazily and still to be made (the next factorization would make
  // it), so that the caller can put that work beside a wait; a system that makes it with itself has nothing
  // to do.
  virtual void prepareBase() {}
  // Takes the constraint set as it now is after the system was out of use (other constraints may have come
  // and gone); throws InputError naming what it cannot take, unchanged then.
  virtual void resume() = 0;

  // Stores the spec in the design's constraint set and puts its terms into the factor; returns its id.
  // Throws InputError for what this field cannot take, leaving the set and the factor unchanged.
  virtual int32_t add(const ConstraintSpec& spec, DesignStats& stats) = 0;
  // The constraint's terms out of the factor, before the set forgets it.
  virtual void remove(const ConstraintSpec& spec, DesignStats& stats) = 0;
  // spec carries its new weight.
  virtual void reweight(const ConstraintSpec& spec, double previousWeight, DesignStats& stats) = 0;
  // Every constraint's terms out of the factor at once, before the set is cleared.
  virtual void clear(DesignStats& stats) = 0;

  virtual void factorNow(DesignStats& stats) = 0;
  // Solves (factoring first when needed) into `field`; throws InputError, `field` unchanged, when the field
  // is not finite.
  virtual void solve(FieldSolution& field, DesignStats& stats) = 0;
  // 3 per vertex from a solve's field.
  virtual void vertexVectors(const FieldSolution& field, std::vector<double>& out) const = 0;

  // The system the design means (base + constraint terms, without the kernel shift) and its right-hand side.
  virtual void assemble(SparseMatrix& A, Eigen::VectorXd& b) = 0;
  virtual SparseMatrix baseMatrix() = 0;  // without shift or constraints, full
  virtual double weightScale() = 0;       // relative weights are multiplied by this
};

// The system of symmetry N (1: the vector field) over the design's mesh and constraint set, both of which
// must outlive it: with prescribed singularities in the set (or settings.exactSingularities), the
// prescribed-singularity system of that N.
// Throws InputError naming what it cannot take (a source on a line field).
std::unique_ptr<FieldSystem> makeFieldSystem(int symmetry, const DesignMesh& mesh, ConstraintSet& constraints,
                                             const FieldSettings& settings);

// The settings' factor options on a system's factor.
void configureFactor(ShiftedFactor& factor, const FieldSettings& settings);

// The factorization's figures and the solve counters of `factor`, into stats.
void reportFactor(const ShiftedFactor& factor, int64_t unknowns, DesignStats& stats);

}  // namespace tvf
