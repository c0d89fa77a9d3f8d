#pragma once
// The field-design session: one mesh with what is derived from it (design/design_mesh.h), a set of
// constraints (constraints/constraint_set.h) and the field system of the chosen symmetry
// (design/field_system.h: the vector field's 1-form system or an N-direction field's power-field system),
// whose factor every edit changes by rank updates. The Designer checks its inputs and dispatches to that
// system; it never asks which kind it is. This is the object the CLI and the wasm bindings drive; it holds
// no UI state.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/numeric_ranges.h"  // the ranges its inputs are checked against
#include "common/sparse_matrix.h"
#include "constraints/constraint_spec.h"
#include "dec/boundary_condition.h"
#include "dec/hodge_star.h"
#include "design/design_stats.h"
#include "field/hodge_decomposition.h"
#include "field/singularities.h"
#include "mesh/feature_edges.h"
#include "mesh/mesh_checks.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"
#include "solver/factored_system.h"  // KeptOrdering

namespace tvf {

class Designer {
 public:
  // Builds topology and checks the mesh; throws InputError naming the first problem if it cannot be designed
  // on.
  explicit Designer(SurfaceMesh mesh);
  ~Designer();
  Designer(Designer&&) noexcept;
  Designer& operator=(Designer&&) noexcept;

  // Base-matrix changes: these mark the factor stale; the next solve (or factor()) refactors.
  void setBoundary(const BoundaryCondition& bc);
  void setGamma(double gamma);
  // N-fold symmetry of the field: 1 is a vector field (the paper's 1-form: every constraint kind, gamma, the
  // boundary condition, Hodge); 2 a line field, 4 a cross field, up to 6 (direction/power_field_system.h:
  // strokes and direction constraints only, free boundary). Strokes and vectors carry over; throws InputError
  // naming the constraints that cannot (sources, sinks, vortices, edge values), leaving the design unchanged.
  void setSymmetry(int symmetry);
  int symmetry() const;
  // N >= 2, even: pull towards principal curvature directions with strength s >= 0 (0: off; 1 about as strong
  // as a weight-1 direction on every face). Throws InputError for N = 1 or odd N with s > 0.
  void setCurvatureAlignment(double s);
  double curvatureAlignment() const;
  void setMetisOrdering(bool metis);  // METIS nested dissection by default; false: AMD
  // Threads for the backward substitution of every solve (solver/factored_system.h; default: the cores there
  // are, up to what the build provides). Refactors at the next solve; the solution does not change.
  void setSolverThreads(int threads);
  int solverThreads() const;
  // The most memory a factorization may take, in bytes; estimated from CHOLMOD's symbolic analysis before the
  // numeric factorization, which is refused (InputError naming both sizes) when it would need more. 0: the
  // machine's physical memory (the default). The wasm bindings pass what is left of the 4 GB address space.
  void setFactorMemoryLimit(double bytes);
  double factorMemoryLimit() const;
  // Whether an added constraint's terms are held beside the field system's factor (vector, line or cross
  // field alike) and applied to the solves by the Woodbury identity (solver/woodbury_correction.h) rather
  // than updated into it first: the field after an edit is ready without waiting for the factor's update,
  // which applyDeferredUpdates() then does (the worker, once the field has gone to the page). Any other
  // change of the factor applies it first. Off by default.
  void setDeferredUpdates(bool defer);
  // Puts a held update into the factor (nothing when there is none); stats().deferredUpdateMs times it.
  void applyDeferredUpdates();
  void factor();

  // Each returns a stable id (> 0). Throws InputError for an impossible constraint (bad face, NaN, ...).
  int32_t addStroke(const std::vector<SurfacePoint>& points, double strength, double weight);
  int32_t addVector(int32_t face, const double vector[3], double weight);
  int32_t addEdge(int32_t i, int32_t j, double value, double weight);
  int32_t addSource(int32_t vertex, double strength);  // strength = total outflow
  int32_t addSink(int32_t vertex, double strength);    // strength = total inflow
  int32_t addVortex(int32_t face, double strength);    // signed circulation, + = counter-clockwise
  // A prescribed singularity (any symmetry; direction/trivial_connection.h): the field has index `index` at
  // interior vertex `vertex`. Throws InputError naming the problem (a boundary or unused vertex, an index
  // that is not a nonzero multiple of 1/N, a vertex that already has one); the design is then unchanged. With
  // singularities the field is a unit N-direction field even for N = 1, and sources, sinks, vortices and edge
  // values are refused (by name) as for N >= 2.
  int32_t addSingularity(int32_t vertex, double index);
  // true: the field has exactly the prescribed singularities, none when none are prescribed (a torus's cross
  // field without any; on a sphere the whole index is then left to the field, "free"). false (the default):
  // with no prescription the field is the smoothest one, singularities wherever it puts them.
  void setExactSingularities(bool exact);
  bool exactSingularities() const;
  // The singularity `id` to another vertex, keeping its id and index (checked as addSingularity checks).
  void moveSingularity(int32_t id, int32_t vertex);
  void remove(int32_t id);                    // throws InputError for an unknown id
  void setWeight(int32_t id, double weight);  // edge-type constraints only
  void setStrength(int32_t id, double strength);
  void clearConstraints();
  // Re-adds a constraint from its spec (ignoring spec.id); returns the new id.
  int32_t add(const ConstraintSpec& spec);

  // Solves (factoring first if needed) and reconstructs all read-outs. After updates it checks the solution
  // (finite, small residual) and refactors once if the updated factor lost precision; a field that is still
  // not finite is refused with an InputError and the previous read-outs stay as they were.
  void solve();
  // How many times solve() found the updated factor wanting and refactored (for tests and stats).
  int32_t precisionRefactors() const;

  // Read-outs; pointers stay valid until the next solve/load. Flat arrays.
  const std::vector<double>& oneForm() const;  // per edge, canonical orientation
  // 3 per face, at barycentres; for N >= 2 one unit representative of the N directions
  // (direction/representative_directions.h), and oneForm() is empty.
  const std::vector<double>& faceVectors() const;
  const std::vector<double>& vertexVectors() const;  // 3 per vertex (N >= 2: a unit representative)
  // Face and vertex vectors (Eq. 4, 5) of any 1-form (one value per edge, oneForm()'s order: a Hodge part,
  // say), by the Whitney maps the solve itself applies, built once per mesh and shared.
  void reconstruct(const double* oneForm, std::vector<double>& faceVectors,
                   std::vector<double>& vertexVectors) const;
  // The field's singularities, each flagged `prescribed` when the design prescribes that index there.
  const std::vector<Singularity>& singularities() const;

  // Sharp features (mesh/feature_edges.h): interior edges whose dihedral angle exceeds `degrees` (0: none
  // detected), plus `add`, minus `remove` (vertex pairs). Faces along a feature take its direction as a
  // strongly weighted term (direction/feature_terms.h); a base change, so the factor is made again. Throws
  // InputError naming a pair that is not a mesh edge, or an angle outside [0, 180]; unchanged then.
  void setFeatures(double degrees, const std::vector<std::array<int32_t, 2>>& add,
                   const std::vector<std::array<int32_t, 2>>& remove);
  // 0 (none) by default, so a design made before features keeps its field; the page starts a design at
  // suggestedFeatureAngle(): 35 on a creased surface, 0 on a faceted curved one.
  double featureAngle() const;
  // How the mesh's edges fold, and the feature angle that suggests for a new design (mesh/feature_edges.h).
  const FoldProfile& foldProfile() const;
  double suggestedFeatureAngle() const;
  const std::vector<std::array<int32_t, 2>>& featureEdgesAdded() const;
  const std::vector<std::array<int32_t, 2>>& featureEdgesRemoved() const;
  const std::vector<int32_t>& featureEdges() const;  // the edges in use, ascending
  const DesignStats& stats() const;
  // The Hodge decomposition (Eq. 3) of the current one-form, computed on each call (two Poisson solves on
  // the mesh's d0, d1 and stars; field/hodge_decomposition.h). Throws InputError before the first solve.
  HodgeDecomposition hodgeDecomposition() const;

  std::vector<ConstraintSpec> constraints() const;  // in the order they were added
  const BoundaryCondition& boundary() const;
  double gamma() const;
  // The system the design means (base + constraint rows, without the kernel shift) and its right-hand side,
  // for checking the update path against an independent solve.
  void assembleSystem(SparseMatrix& A, Eigen::VectorXd& b);
  // The field system's base matrix without shift or constraints: for a vector field the boundary-modified
  // Laplacian (or bi-Laplacian), for N >= 2 the connection Laplacian with the boundary's terms.
  SparseMatrix baseMatrix();
  double weightScale();  // weights are multiplied by this (the mean diagonal of the base matrix)
  Eigen::VectorXd textureFaceVectors() const;  // 2 per face when the mesh has UVs

  const SurfaceMesh& mesh() const;
  // meshHash(mesh()) (mesh/mesh_hash.h), made on first use: every saved design carries it, and the page saves
  // one after each edit (7 ms at 832k faces in wasm).
  uint64_t meshHash() const;
  // The field system's fill-reducing ordering (FactoredSystem::keptOrdering: empty before the first
  // factorization), to keep beyond this designer; and one kept from an earlier designer on the same mesh,
  // which the next factorization of the same pattern uses instead of ordering again
  // (FactoredSystem::adoptOrdering).
  // keepFieldSymbolic: whether fieldOrdering() carries the symbolic factor of the field system's next
  // analysis too (FactoredSystem::setKeepSymbolic), for a cache that skips the analysis as well;
  // fieldOrderingIsNew: whether there is anything in it for such a cache to store
  // (FactoredSystem::keptOrderingIsNew).
  KeptOrdering fieldOrdering() const;
  bool adoptFieldOrdering(KeptOrdering kept);
  void keepFieldSymbolic(bool keep);
  bool fieldOrderingIsNew() const;
  // Frees the field systems' numeric factors and what they are made from (FieldSystem::releaseMemory),
  // keeping the design, the field and the orderings: the next solve assembles and factors again. For a model
  // about to be replaced, whose memory its successor's then takes (solver/factor_memory.h).
  void releaseFactors();
  // The field system's matrix assembled now, as the next solve would (FieldSystem::prepareBase): a model
  // about to be factored can have that done while its caller waits for something else (web/core/worker/
  // load-ops.js: the kept analysis and the picking parts read from IndexedDB).
  void prepareSystem();
  const std::vector<int32_t>& edgeVertices() const;  // 2 per edge, lower index first
  // Derived from the mesh once, at construction; exports and benchmarks read them rather than derive again.
  const MeshTopology& topology() const;
  // What the construction's check noted but did not refuse (unused vertices, say), for the info report.
  const std::vector<MeshProblem>& meshNotes() const;
  const MeshGeometry& geometry() const;
  // Unit area-weighted vertex normals, made once (DesignMesh): the stripes' families read them.
  const std::vector<double>& vertexNormals() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace tvf
