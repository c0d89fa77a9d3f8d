#pragma once
// What the design's last edits, factorization and solve took and found: the session's stats() read-out, the
// benchmarks' figures and the tests' checks (no edit refactors, no solve lost precision).
#include <cstdint>
#include <string>
#include <vector>

namespace tvf {

struct DesignStats {
  double analyzeMs = 0, factorMs = 0, updateMs = 0, solveMs = 0, reconstructMs = 0;
  double convertMs = 0;     // of factorMs, the factor turned into LDL' for the updates
  double dissectionMs = 0;  // of analyzeMs, the nested dissection of the mesh's vertex graph (on the threads)
  // The last deferred update put into the factor after its solve (setDeferredUpdates); updateMs is then
  // what the edit itself took: the update's correction for the solves.
  double deferredUpdateMs = 0;
  double rowsMs = 0;            // the last added constraint's rows (a stroke's surface walk)
  double rhsMs = 0;             // the last solve's right-hand side
  bool analysisReused = false;  // the last factorization reused the ordering (unchanged sparsity pattern)
  bool symbolicReused = false;  // ... and a kept symbolic factor: no analysis at all (solver/kept_symbolic.h)
  // Solves that found the updated factor wanting (backward error beyond round-off) and refactored: a
  // benchmark that times updates must see none.
  int32_t precisionRefactors = 0;
  // Solves whose forward substitution was redone only on the paths the edits changed (all since the mesh
  // was loaded; solver/forward_solution.h).
  int64_t incrementalSolves = 0;
  // Solves (and refinement steps) whose backward substitution went by supernodes (the wasm build's;
  // solver/backward_substitution.h), since the factored system was made.
  int64_t supernodalSolves = 0;
  double nnzPerRowM = 0, nnzPerRowL = 0;
  int32_t positiveAreaFallbackVertices = 0;
  std::string kernelHandling;  // how the kernel of M was made definite
  double kernelShift = 0;      // the relative diagonal shift that made the factorization succeed
  std::vector<std::string> warnings;
  std::string factorKind;  // e.g. "supernodal LL' (AMD)"
  // Threads the last numeric factorization ran on; when more were asked for and it ran on one, why (a
  // helper thread that failed to run, a tree with no subtrees worth splitting).
  int32_t factorThreads = 1;
  int32_t factorGroups = 1;  // of them, the groups of subtrees factored side by side before the top
  std::string singleThreadWhy;
  int32_t symmetry = 1;  // N of the field solved last (1: a vector field, the paper's 1-form)
  // Numeric factorizations of the system in use since it was made: a constraint edit adds none (rank
  // updates).
  int64_t factorizations = 0;
  // The smoothest unconstrained N-field's inverse iterations and eigenvalue (0 for any other solve).
  int32_t inverseIterations = 0;
  double smoothestEigenvalue = 0;
  // Prescribed singularities (design/prescribed_field_system.h): "none"; "exact" when the prescribed indices
  // account for all the index the surface needs (their sum is the Euler characteristic, or the surface has a
  // boundary to take the rest) and the field is the trivial connection's, with exactly those singularities;
  // "free" when the field places freeIndex = eulerCharacteristic - prescribedIndex itself.
  std::string singularityMode = "none";
  int32_t eulerCharacteristic = 0;
  double prescribedIndex = 0, freeIndex = 0;
  double connectionMs = 0;   // the last change of singularities: the trivial connection's solve
  int32_t featureEdges = 0;  // edges the field follows as features (detected by angle, plus or minus edits)
};

}  // namespace tvf
