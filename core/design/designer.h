#pragma once
// The field-design session: one mesh, its boundary condition and gamma, a factored system, and a set of
// constraints edited through rank-1 updates of that factor. This is the object the CLI and the wasm
// bindings drive; it holds no UI state.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mesh/surface_mesh.h"

namespace tvf {

struct SurfacePoint {
  int32_t face;
  double bary[3];
};

// "free", or a fixed angle beta per boundary edge (tangential = pi/2, normal = 0), with optional overrides.
struct BoundaryCondition {
  bool free = true;
  double angle = 0.0;  // used when !free
  struct EdgeAngle {
    int32_t i, j;
    double angle;
  };
  std::vector<EdgeAngle> perEdge;  // overrides, vertex pairs in any order

  static BoundaryCondition makeFree() { return {}; }
  static BoundaryCondition fixedAngle(double beta) { return {false, beta, {}}; }
  static BoundaryCondition tangential();
  static BoundaryCondition normal() { return fixedAngle(0.0); }
};

// Ranges every numeric input is checked against, in the core so that the CLI, the wasm bindings and design
// files share one check (documented in docs/design-format.md, "Numeric ranges"). Weights are relative to the
// mean diagonal of the system matrix: a constraint 1e8 times stiffer than the surface is already exact to
// about 1e-8, and adding then removing it again is undone by the factor to round-off (see kDowndateBudget in
// designer.cpp). Magnitudes (strengths, vector components, edge values) bound the field well inside double
// range on any mesh whose coordinates stay below 1e100.
constexpr double kMinWeight = 1e-8;
constexpr double kMaxWeight = 1e8;
constexpr double kMaxMagnitude = 1e12;
constexpr double kMaxGamma = 1e6;

enum class ConstraintKind { Stroke, Vector, Edge, Source, Sink, Vortex };

// What the user asked for, kept verbatim so a design can be saved and replayed exactly.
struct ConstraintSpec {
  int32_t id = 0;
  ConstraintKind kind = ConstraintKind::Edge;
  std::vector<SurfacePoint> points;  // stroke
  int32_t element = -1;              // face (vector, vortex) or vertex (source, sink)
  int32_t edge[2] = {-1, -1};        // edge: vertex pair, value along i -> j
  double vector[3] = {0, 0, 0};
  double value = 0;
  double strength = 1;  // stroke: |t|; source/sink: total flux; vortex: signed circulation
  double weight = 1;    // edge-type constraints: relative to the mean diagonal of the system matrix
};

struct Singularity {
  int32_t vertex;
  double index;
};

struct DesignStats {
  double analyzeMs = 0, factorMs = 0, updateMs = 0, solveMs = 0, reconstructMs = 0;
  double rowsMs = 0;            // the last added constraint's rows (a stroke's surface walk)
  double rhsMs = 0;             // the last solve's right-hand side
  bool analysisReused = false;  // the last factorization reused the ordering (unchanged sparsity pattern)
  double nnzPerRowM = 0, nnzPerRowL = 0;
  int32_t positiveAreaFallbackVertices = 0;
  std::string kernelHandling;  // how the kernel of M was made definite
  double kernelShift = 0;      // the relative diagonal shift that made the factorization succeed
  std::vector<std::string> warnings;
  std::string factorKind;  // e.g. "supernodal LL' (AMD)"
};

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
  void setMetisOrdering(bool metis);  // METIS nested dissection by default; false: AMD
  // The most memory a factorization may take, in bytes; estimated from CHOLMOD's symbolic analysis before the
  // numeric factorization, which is refused (InputError naming both sizes) when it would need more. 0: the
  // machine's physical memory (the default). The wasm bindings pass what is left of the 4 GB address space.
  void setFactorMemoryLimit(double bytes);
  double factorMemoryLimit() const;
  void factor();

  // Each returns a stable id (> 0). Throws InputError for an impossible constraint (bad face, NaN, ...).
  int32_t addStroke(const std::vector<SurfacePoint>& points, double strength, double weight);
  int32_t addVector(int32_t face, const double vector[3], double weight);
  int32_t addEdge(int32_t i, int32_t j, double value, double weight);
  int32_t addSource(int32_t vertex, double strength);  // strength = total outflow
  int32_t addSink(int32_t vertex, double strength);    // strength = total inflow
  int32_t addVortex(int32_t face, double strength);    // signed circulation, + = counter-clockwise
  void remove(int32_t id);                             // throws InputError for an unknown id
  void setWeight(int32_t id, double weight);           // edge-type constraints only
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
  const std::vector<double>& oneForm() const;        // per edge, canonical orientation
  const std::vector<double>& faceVectors() const;    // 3 per face, at barycentres
  const std::vector<double>& vertexVectors() const;  // 3 per vertex
  const std::vector<Singularity>& singularities() const;
  const DesignStats& stats() const;

  std::vector<ConstraintSpec> constraints() const;  // in the order they were added
  const BoundaryCondition& boundary() const;
  double gamma() const;
  // The system the design means (base + constraint rows, without the kernel shift) and its right-hand side,
  // for checking the update path against an independent solve.
  void assembleSystem(Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A, Eigen::VectorXd& b);
  // The plain boundary-modified Laplacian (or bi-Laplacian) without shift or constraints.
  const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& baseMatrix();
  double weightScale();  // weights are multiplied by this (the mean diagonal of the base matrix)
  Eigen::VectorXd textureFaceVectors() const;  // 2 per face when the mesh has UVs

  const SurfaceMesh& mesh() const;
  const std::vector<int32_t>& edgeVertices() const;  // 2 per edge, lower index first
  std::string infoJson() const;                      // same keys as `tvf info`

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace tvf
