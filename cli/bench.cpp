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
      const int32_t g = t.edgeFaces[2 * e] == f ? t.edgeFaces[2 * e + 1] : t.edgeFaces[2 * e];
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

nlohmann::json runBench(const std::string& meshPath, int repeat, double gamma, bool metis) {
  Designer designer(loadMesh(meshPath));
  designer.setGamma(gamma);
  std::vector<double> analyze, factor, solve, update, stroke, strokeUpdate, strokeRows, strokeRhs,
      strokeSolve, reconstruct;
  const int32_t nF = designer.mesh().numFaces();
  int strokeEdges = 0;  // edges the benchmark stroke crosses (one per step between adjacent faces)
  const MeshTopology topology = buildTopology(designer.mesh());  // for the benchmark's stroke paths only
  for (int r = 0; r < repeat; ++r) {
    designer.clearConstraints();
    // A fresh factored system: the designer would otherwise reuse the first repeat's ordering.
    designer.setMetisOrdering(metis);
    designer.factor();
    analyze.push_back(designer.stats().analyzeMs);
    factor.push_back(designer.stats().factorMs);
    designer.addSource(designer.mesh().triangles[0], 1.0);
    designer.solve();
    solve.push_back(designer.stats().solveMs);
    reconstruct.push_back(timeMs([&] {
                            designer.solve();
                            designer.vertexVectors();
                          }) -
                          designer.stats().solveMs);
    const int32_t face = (r * 7919 + 13) % nF;
    const int32_t i = designer.mesh().triangles[3 * face], j = designer.mesh().triangles[3 * face + 1];
    const int32_t id = designer.addEdge(i, j, 0.1, 1.0);
    update.push_back(designer.stats().updateMs);
    designer.remove(id);
    const auto points = stripStroke(designer.mesh(), topology, (r * 104729 + 7) % nF, 50);
    // Mouse-up to new one-form: the surface walk, the rank-k update and the solve (reconstruction is
    // reported on its own).
    const double total = timeMs([&] {
      designer.addStroke(points, 1.0, 1.0);
      designer.solve();
    });
    stroke.push_back(total - designer.stats().reconstructMs);
    strokeEdges = static_cast<int>(points.size()) - 1;
    strokeUpdate.push_back(designer.stats().updateMs);
    strokeRows.push_back(designer.stats().rowsMs);
    strokeRhs.push_back(designer.stats().rhsMs);
    strokeSolve.push_back(designer.stats().solveMs);
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
          {"strokeUpdateMs", median(strokeUpdate)},
          {"strokeRowsMs", median(strokeRows)},
          {"strokeRhsMs", median(strokeRhs)},
          {"strokeSolveMs", median(strokeSolve)},
          {"strokeEdges", strokeEdges},
          {"reconstructMs", median(reconstruct)},
          {"repeat", repeat},
          {"gamma", gamma},
          {"ordering", metis ? "metis" : "amd"},
          {"factorKind", designer.stats().factorKind}};
}

}  // namespace tvf
