#pragma once
// Everything synthesis needs to know about one exemplar, computed once and cached by the caller: the toroidal
// Gaussian stack, and per stack level the appearance-space vectors, the reduced synthesis-neighbourhood vectors
// and the k-coherence candidate sets. `gpuTables` lays a level out as the flat float arrays the WebGL2
// synthesizer uploads as textures and uniforms (web/synthesis/).
#include <cstdint>
#include <vector>

#include "texture/appearance_space.h"
#include "texture/gaussian_stack.h"
#include "texture/k_coherence.h"
#include "texture/neighbourhood_space.h"

namespace tvf {

struct AnalysisOptions {
  int appearanceDims = 8;     // PCA of the 5x5 colour neighbourhoods (the GPU layout needs 8)
  int neighbourhoodDims = 8;  // PCA of the 8-neighbour appearance neighbourhoods (the GPU layout needs 8)
  int k = 2;                  // k-coherence candidates per pixel
  double tapSigma = 1.0;      // Gaussian weight of the 5x5 taps (in taps)
  int covarianceSubsample = 4;  // covariances from one pixel in 4 (covarianceSubset; 4k samples at 128^2)
  int exclusionRadius = -1;   // near-self exclusion for k-coherence; -1: min(max(2, h_s / 2), max(2, size / 8))
};

struct AnalysisLevel {
  AppearanceLevel appearance;
  NeighbourhoodLevel neighbourhood;
  KCoherenceLevel candidates;
};

struct AnalysisTimings {
  double stackMs = 0, appearanceMs = 0, neighbourhoodMs = 0, kCoherenceMs = 0, totalMs = 0;
};

struct ExemplarAnalysis {
  GaussianStack stack;
  std::vector<AnalysisLevel> levels;  // one per stack level
  AnalysisOptions options;
  AnalysisTimings timings;
  int size() const { return stack.size(); }
  int numLevels() const { return static_cast<int>(levels.size()); }
};

ExemplarAnalysis analyzeExemplar(const ExemplarImage& exemplar, const AnalysisOptions& options = {});

// One level as flat arrays (row-major, pixel index y * size + x):
struct GpuLevelTables {
  std::vector<float> colour;         // pixels x 4: stack-level RGB, 1
  std::vector<float> appearance;     // pixels x 8
  std::vector<float> neighbourhood;  // pixels x 8
  std::vector<float> candidates;     // pixels x 4: (x, y) of the first two k-coherence candidates
  // 8 blocks (one per neighbour offset, kNeighbourOffsets order) of 8 x 8, block k entry (i, j) at
  // 64 k + 8 i + j = weight of appearance component i in reduced dimension j; then `projectionOffset` = axes^T mean.
  std::vector<float> projection;
  std::vector<float> projectionOffset;  // 8
};
// Throws InputError unless both reduced dimensions are 8 and k >= 2.
GpuLevelTables gpuTables(const ExemplarAnalysis& analysis, int level);

}  // namespace tvf
