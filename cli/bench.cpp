#include "cli/bench.h"

#include <algorithm>
#include <chrono>
#include <functional>

#include "design/designer.h"
#include "io/mesh_io.h"

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

// Barycentres of a strip of adjacent faces: a stroke that crosses about `crossings` edges.
std::vector<SurfacePoint> stripStroke(const SurfaceMesh& mesh, int32_t start, int crossings) {
  std::vector<SurfacePoint> points;
  std::vector<int32_t> faces{start};
  // Neighbours through shared vertex pairs; a small local search is enough for a benchmark path.
  std::vector<int32_t> visited{start};
  int32_t f = start;
  for (int step = 0; step < crossings; ++step) {
    int32_t next = -1;
    for (int32_t g = std::max(0, f - 64); g < std::min(mesh.numFaces(), f + 64) && next < 0; ++g) {
      if (std::find(visited.begin(), visited.end(), g) != visited.end()) continue;
      int shared = 0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) shared += mesh.triangles[3 * f + a] == mesh.triangles[3 * g + b];
      if (shared == 2) next = g;
    }
    if (next < 0) break;
    visited.push_back(next);
    f = next;
  }
  for (const int32_t g : visited) points.push_back({g, {1.0 / 3, 1.0 / 3, 1.0 / 3}});
  return points;
}

}  // namespace

nlohmann::json runBench(const std::string& meshPath, int repeat, double gamma, bool metis) {
  Designer designer(loadMesh(meshPath));
  designer.setGamma(gamma);
  designer.setMetisOrdering(metis);
  std::vector<double> analyze, factor, solve, update, stroke, reconstruct;
  const int32_t nF = designer.mesh().numFaces();
  for (int r = 0; r < repeat; ++r) {
    designer.clearConstraints();
    designer.factor();
    analyze.push_back(designer.stats().analyzeMs);
    factor.push_back(designer.stats().factorMs);
    designer.addSource(designer.mesh().triangles[0], 1.0);
    designer.solve();
    solve.push_back(designer.stats().solveMs);
    reconstruct.push_back(designer.stats().reconstructMs);
    const int32_t face = (r * 7919 + 13) % nF;
    const double u[3] = {1, 0, 0};
    const int32_t i = designer.mesh().triangles[3 * face], j = designer.mesh().triangles[3 * face + 1];
    const int32_t id = designer.addEdge(i, j, 0.1, 1.0);
    update.push_back(designer.stats().updateMs);
    designer.remove(id);
    (void)u;
    const auto points = stripStroke(designer.mesh(), (r * 104729 + 7) % nF, 50);
    stroke.push_back(timeMs([&] {
      designer.addStroke(points, 1.0, 1.0);
      designer.solve();
    }));
  }
  const auto& ev = designer.edgeVertices();
  return {{"mesh", meshPath},
          {"edges", ev.size() / 2},
          {"nnzPerRowM", designer.stats().nnzPerRowM},
          {"nnzPerRowL", designer.stats().nnzPerRowL},
          {"analyzeMs", median(analyze)},
          {"factorMs", median(factor)},
          {"solveMs", median(solve)},
          {"updateMs", median(update)},
          {"strokeUpdateSolveMs", median(stroke)},
          {"reconstructMs", median(reconstruct)},
          {"repeat", repeat},
          {"gamma", gamma},
          {"ordering", metis ? "metis" : "amd"},
          {"factorKind", designer.stats().factorKind}};
}

}  // namespace tvf
