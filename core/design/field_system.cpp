#include "design/field_system.h"

#include <algorithm>

#include "design/direction_field_system.h"
#include "design/one_form_system.h"
#include "design/prescribed_field_system.h"

namespace tvf {

std::unique_ptr<FieldSystem> makeFieldSystem(int symmetry, const DesignMesh& mesh, ConstraintSet& constraints,
                                             const FieldSettings& settings) {
  if (settings.exactSingularities || !constraints.specsOf(ConstraintKind::Singularity).empty())
    return std::make_unique<PrescribedFieldSystem>(symmetry, mesh, constraints, settings);
  if (symmetry == 1) return std::make_unique<OneFormSystem>(mesh, constraints, settings);
  return std::make_unique<DirectionFieldSystem>(symmetry, mesh, constraints, settings);
}

void configureFactor(ShiftedFactor& factor, const FieldSettings& settings) {
  factor.setOrdering(settings.ordering);
  if (settings.threads > 0) factor.setThreads(settings.threads);
  factor.setMemoryLimit(settings.memoryLimit);
  factor.setDeferredUpdates(settings.deferUpdates);
}

void reportFactor(const ShiftedFactor& factor, int64_t unknowns, DesignStats& stats) {
  const FactorReport& r = factor.report();
  stats.analyzeMs = r.analyzeMs;
  stats.analysisReused = r.analysisReused;
  stats.symbolicReused = r.symbolicReused;
  stats.factorMs = r.factorMs;
  stats.convertMs = r.convertMs;
  stats.dissectionMs = r.dissectionMs;
  stats.nnzPerRowL =
      static_cast<double>(r.factorNonzeros) / static_cast<double>(std::max<int64_t>(1, unknowns));
  stats.kernelShift = r.kernelShift;
  stats.kernelHandling = r.kernelHandling;
  stats.factorKind = r.factorKind;
  stats.factorThreads = r.factorThreads;
  stats.factorGroups = r.factorGroups;
  stats.singleThreadWhy = r.singleThreadWhy;
  stats.factorizations = r.factorizations;
  stats.precisionRefactors = factor.precisionRefactors();
  stats.incrementalSolves = factor.incrementalSolves();
  stats.supernodalSolves = factor.supernodalSolves();
}

}  // namespace tvf
