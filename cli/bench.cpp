#include "cli/bench.h"

#include <algorithm>
#include <chrono>
#include <functional>

#include "design/designer.h"
#include "io/mesh_io.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"

namespace tvf {
namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double timeMs(const std::function<void()>& f) {
  const auto start = Clock::now();
  f();
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Barycentres of a strip of adjacent faces heading away from the start: a stroke crossing ~`crossings` edges.
std::vector<SurfacePoint> stripStroke(const SurfaceMesh& mesh, const MeshTopology& t, int32_t start,
                                      int crossings) {
  const auto centre = [&](int32_t f) {
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    return Eigen::Vector3d((p[0] + p[1] + p[2]) / 3);
  };
  const Eigen::Vector3d origin = centre(start);
  std::vector<SurfacePoint> points{{start, {1.0 / 3, 1.0 / 3, 1.0 / 3}}};
  int32_t f = start;
  for (int step = 0; step < crossings; ++step) {
    int32_t next = -1;
    double farthest = -1;
    for (int c = 0; c < 3; ++c) {
      const int32_t e = t.edgeOf(f, c);
      const int32_t g = t.otherFace(e, f);
      if (g < 0) continue;
      const double d = (centre(g) - origin).norm();
      if (d > farthest) farthest = d, next = g;
    }
    if (next < 0) break;
    points.push_back({next, {1.0 / 3, 1.0 / 3, 1.0 / 3}});
    f = next;
  }
  return points;
}

}  // namespace

namespace {

// Timings of one ordering over the repeats.
struct Samples {
  std::vector<double> analyze, factor, solve, update, stroke, strokeUpdate, strokeRows, strokeRhs,
      strokeSolve, reconstruct, smoothest, deferredStroke, deferredCorrection, deferredUpdate;
  double nnzPerRowM = 0, nnzPerRowL = 0;
  int strokeEdges = 0;      // edges the benchmark stroke crosses (one per step between adjacent faces)
  int strokeRefactors = 0;  // stroke solves that refactored (an updated factor found wanting): timings void
  int strokeIncrementalSolves = 0;  // stroke solves whose forward substitution was incremental
  std::string factorKind;
};

void runRepeat(Designer& designer, int r, bool metis, Samples& s) {
  const int32_t nF = designer.mesh().numFaces();
  designer.clearConstraints();
  // A fresh factored system: the designer would otherwise reuse the previous repeat's ordering.
  designer.setMetisOrdering(metis);
  designer.factor();
  s.analyze.push_back(designer.stats().analyzeMs);
  s.factor.push_back(designer.stats().factorMs);
  const bool directions = designer.symmetry() > 1;
  if (directions) {
    designer.solve();  // the smoothest field: inverse iteration with the factor
    s.smoothest.push_back(designer.stats().solveMs);
    const double along[3] = {1, 0.3, 0.1};
    designer.addVector(0, along, 1.0);
  } else {
    designer.addSource(designer.mesh().triangles[0], 1.0);
  }
  designer.solve();
  s.solve.push_back(designer.stats().solveMs);
  s.reconstruct.push_back(timeMs([&] {
                            designer.solve();
                            designer.vertexVectors();
                          }) -
                          designer.stats().solveMs);
  const int32_t face = (r * 7919 + 13) % nF;
  const int32_t i = designer.mesh().triangles[3 * face], j = designer.mesh().triangles[3 * face + 1];
  const double dir[3] = {0.2, 1, 0.4};
  const int32_t id = directions ? designer.addVector(face, dir, 1.0) : designer.addEdge(i, j, 0.1, 1.0);
  s.update.push_back(designer.stats().updateMs);
  designer.remove(id);
  designer.solve();  // as the page does after every edit: the stroke starts from a solved design
  const auto points = stripStroke(designer.mesh(), designer.topology(), (r * 104729 + 7) % nF, 50);
  const int32_t refactorsBefore = designer.stats().precisionRefactors;
  const int64_t incrementalBefore = designer.stats().incrementalSolves;
  // Mouse-up to new one-form: the surface walk, the rank-k update, the right-hand side and the solve
  // (reconstruction is reported on its own).
  int32_t strokeId = 0;
  const double total = timeMs([&] {
    strokeId = designer.addStroke(points, 1.0, 1.0);
    designer.solve();
  });
  s.stroke.push_back(total - designer.stats().reconstructMs);
  s.strokeEdges = static_cast<int>(points.size()) - 1;
  s.strokeUpdate.push_back(designer.stats().updateMs);
  s.strokeRows.push_back(designer.stats().rowsMs);
  s.strokeRhs.push_back(designer.stats().rhsMs);
  s.strokeSolve.push_back(designer.stats().solveMs);
  s.strokeRefactors += designer.stats().precisionRefactors - refactorsBefore;
  s.strokeIncrementalSolves += static_cast<int>(designer.stats().incrementalSolves - incrementalBefore);
  if (!directions) {
    // The same stroke again with its update held beside the factor (Designer::setDeferredUpdates): what the
    // worker does before the field goes to the page (the correction and the solve through it), and the
    // update put into the factor after.
    designer.remove(strokeId);
    designer.solve();
    designer.setDeferredUpdates(true);
    s.deferredStroke.push_back(timeMs([&] {
                                 designer.addStroke(points, 1.0, 1.0);
                                 designer.solve();
                               }) -
                               designer.stats().reconstructMs);
    s.deferredCorrection.push_back(designer.stats().updateMs);
    designer.applyDeferredUpdates();
    s.deferredUpdate.push_back(designer.stats().deferredUpdateMs);
    designer.setDeferredUpdates(false);
  }
  s.nnzPerRowM = designer.stats().nnzPerRowM;
  s.nnzPerRowL = designer.stats().nnzPerRowL;
  s.factorKind = designer.stats().factorKind;
}

nlohmann::json summary(const Samples& s, bool metis) {
  return {{"nnzPerRowM", s.nnzPerRowM},
          {"nnzPerRowL", s.nnzPerRowL},
          {"analyzeMs", median(s.analyze)},
          {"factorMs", median(s.factor)},
          {"solveMs", median(s.solve)},
          {"updateMs", median(s.update)},
          {"strokeUpdateSolveMs", median(s.stroke)},
          {"strokeUpdateMs", median(s.strokeUpdate)},
          {"strokeRowsMs", median(s.strokeRows)},
          {"strokeRhsMs", median(s.strokeRhs)},
          {"strokeSolveMs", median(s.strokeSolve)},
          {"strokeEdges", s.strokeEdges},
          {"deferredStrokeSolveMs", median(s.deferredStroke)},
          {"deferredStrokeCorrectionMs", median(s.deferredCorrection)},
          {"deferredStrokeUpdateMs", median(s.deferredUpdate)},
          {"strokeRefactors", s.strokeRefactors},
          {"strokeIncrementalSolves", s.strokeIncrementalSolves},
          {"reconstructMs", median(s.reconstruct)},
          {"smoothestMs", median(s.smoothest)},
          {"ordering", metis ? "metis" : "amd"},
          {"factorKind", s.factorKind}};
}

}  // namespace

nlohmann::json runBench(const std::string& meshPath, int repeat, double gamma,
                        const std::vector<bool>& orderings, int threads, int symmetry) {
  Designer designer(loadMesh(meshPath));
  designer.setGamma(gamma);
  designer.setSymmetry(symmetry);
  if (threads > 0) designer.setSolverThreads(threads);
  std::vector<Samples> samples(orderings.size());
  // Orderings interleaved repeat by repeat, so that their ratios see the same machine state.
  for (int r = 0; r < repeat; ++r)
    for (size_t o = 0; o < orderings.size(); ++o) runRepeat(designer, r, orderings[o], samples[o]);
  nlohmann::json out = {{"mesh", meshPath},     {"edges", designer.edgeVertices().size() / 2},
                        {"repeat", repeat},     {"gamma", gamma},
                        {"symmetry", symmetry}, {"threads", designer.solverThreads()}};
  if (orderings.size() == 1) {
    out.update(summary(samples[0], orderings[0]));
    return out;
  }
  for (size_t o = 0; o < orderings.size(); ++o)
    out[orderings[o] ? "metis" : "amd"] = summary(samples[o], orderings[o]);
  return out;
}

}  // namespace tvf
