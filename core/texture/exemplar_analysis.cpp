#include "texture/exemplar_analysis.h"

#include <algorithm>
#include <chrono>

#include "common/stopwatch.h"
#include "mesh/surface_mesh.h"

namespace tvf {

ExemplarAnalysis analyzeExemplar(const ExemplarImage& exemplar, const AnalysisOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ExemplarAnalysis out;
  out.options = options;
  auto t = std::chrono::steady_clock::now();
  out.stack = buildGaussianStack(exemplar);
  out.timings.stackMs = msSince(t);
  const int m = out.stack.size();
  AppearanceOptions ao;
  ao.dims = options.appearanceDims;
  ao.tapSigma = options.tapSigma;
  ao.covarianceSubsample = options.covarianceSubsample;
  for (int s = 0; s < out.stack.numLevels(); ++s) {
    AnalysisLevel level;
    t = std::chrono::steady_clock::now();
    level.appearance = appearanceLevel(out.stack, s, ao);
    out.timings.appearanceMs += msSince(t);
    t = std::chrono::steady_clock::now();
    level.neighbourhood =
        neighbourhoodLevel(level.appearance, m, options.neighbourhoodDims, options.covarianceSubsample);
    out.timings.neighbourhoodMs += msSince(t);
    t = std::chrono::steady_clock::now();
    KCoherenceOptions ko;
    ko.k = options.k;
    const int h = GaussianStack::spacing(s);
    ko.radius = options.exclusionRadius >= 0 ? options.exclusionRadius
                                             : std::min(std::max(2, h / 2), std::max(2, m / 8));
    ko.step = std::max(1, h / 2);
    level.candidates = kCoherence(level.neighbourhood.vectors, m, ko);
    out.timings.kCoherenceMs += msSince(t);
    out.levels.push_back(std::move(level));
  }
  out.timings.totalMs = msSince(start);
  return out;
}

GpuLevelTables gpuTables(const ExemplarAnalysis& analysis, int s) {
  if (s < 0 || s >= analysis.numLevels()) throw InputError("gpuTables: no such level");
  const AnalysisLevel& level = analysis.levels[s];
  if (level.appearance.vectors.cols() != 8 || level.neighbourhood.vectors.cols() != 8 ||
      level.candidates.k < 2)
    throw InputError(
        "gpuTables: the GPU layout needs 8 appearance and 8 neighbourhood dimensions and k >= 2");
  const int m = analysis.size(), n = m * m, k = level.candidates.k;
  GpuLevelTables g;
  g.colour.resize(4 * static_cast<size_t>(n));
  g.appearance.resize(8 * static_cast<size_t>(n));
  g.neighbourhood.resize(8 * static_cast<size_t>(n));
  g.candidates.resize(4 * static_cast<size_t>(n));
  const ExemplarImage& img = analysis.stack.levels[s];
  for (int p = 0; p < n; ++p) {
    for (int c = 0; c < 3; ++c) g.colour[4 * p + c] = img.rgb[3 * p + c];
    g.colour[4 * p + 3] = 1;
    for (int c = 0; c < 8; ++c) {
      g.appearance[8 * p + c] = level.appearance.vectors(p, c);
      g.neighbourhood[8 * p + c] = level.neighbourhood.vectors(p, c);
    }
    for (int j = 0; j < 2; ++j) {
      const int32_t q = level.candidates.candidates[static_cast<size_t>(p) * k + j];
      g.candidates[4 * p + 2 * j] = static_cast<float>(q % m);
      g.candidates[4 * p + 2 * j + 1] = static_cast<float>(q / m);
    }
  }
  const PcaBasis& b = level.neighbourhood.basis;
  g.projection.resize(8 * 64);
  for (int nb = 0; nb < 8; ++nb)
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j) g.projection[64 * nb + 8 * i + j] = b.axes(8 * nb + i, j);
  g.projectionOffset.resize(8);
  const Eigen::VectorXf offset = b.axes.transpose() * b.mean;
  for (int j = 0; j < 8; ++j) g.projectionOffset[j] = offset[j];
  return g;
}

}  // namespace tvf
