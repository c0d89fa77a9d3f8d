#include "cli/bench.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <set>

#include "cli/bench_timing.h"
#include "cli/cholmod_baseline.h"
#include "common/input_error.h"
#include "design/designer.h"
#include "io/mesh_io.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"

namespace tvf {
namespace {

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

// Whether the designer takes a singularity of this index at v (interior, used by a face, a one-ring that can
// show it: the checks addSingularity makes). The designer is left as it was.
bool carries(Designer& designer, int32_t v, double index) {
  try {
    designer.remove(designer.addSingularity(v, index));
    return true;
  } catch (const InputError&) {
    return false;
  }
}

// The first vertex from `start` on (cyclically) that can carry a singularity of +-index and is not in
// `used`; -1 when there is none.
int32_t freeVertex(Designer& designer, int32_t start, const std::set<int32_t>& used, double index) {
  const MeshTopology& t = designer.topology();
  for (int32_t k = 0; k < t.numVertices; ++k) {
    const int32_t v = (start + k) % t.numVertices;
    if (!used.count(v) && carries(designer, v, index) && carries(designer, v, -index)) return v;
  }
  return -1;
}

// A neighbour of v across an edge that can carry a singularity (one step of a drag), not in `used`.
int32_t freeNeighbour(Designer& designer, int32_t v, const std::set<int32_t>& used, double index) {
  const MeshTopology& t = designer.topology();
  for (int32_t k = t.vertexEdgeStart[v]; k < t.vertexEdgeStart[v + 1]; ++k) {
    const int32_t e = t.vertexEdgeList[k];
    const int32_t w = t.edgeVertices[2 * e] == v ? t.edgeVertices[2 * e + 1] : t.edgeVertices[2 * e];
    if (!used.count(w) && carries(designer, w, index) && carries(designer, w, -index)) return w;
  }
  return -1;
}

}  // namespace

namespace {

// Timings of one ordering over the repeats.
struct Samples {
  std::vector<double> analyze, dissection, factor, convert, solve, update, stroke, strokeUpdate, strokeRows,
      strokeRhs, strokeSolve, reconstruct, smoothest, deferredStroke, deferredCorrection, deferredUpdate;
  double nnzPerRowM = 0, nnzPerRowL = 0;
  int strokeEdges = 0;      // edges the benchmark stroke crosses (one per step between adjacent faces)
  int strokeRefactors = 0;  // stroke solves that refactored (an updated factor found wanting): timings void
  int strokeIncrementalSolves = 0;  // stroke solves whose forward substitution was incremental
  // Prescribed singularities (timeSingularityEdits): a +1/N, -1/N pair placed in one step, one of them
  // moved, with every index the surface needs prescribed (exact); one moved with none else (free).
  std::vector<double> singularityPlace, singularityMove, singularityFreeMove;
  int64_t singularityFactorizations = 0;  // numeric factorizations the exact edits made
  std::string singularityMode;            // the mode of the exact edits' field, as the designer reports it
  std::string factorKind;
  int factorGroups = 1;  // DesignStats::factorGroups
};

// Prescribed singularities edited as the page's Singularity tool does, each edit timed with its solve and
// read-outs. First with every index the surface needs prescribed, so that the field has exactly the
// prescribed singularities (exact): on a closed surface |chi| N singularities of index sign(chi)/N spread
// over it (untimed), then a +1/N, -1/N pair drawn out in one step (the total stays chi) and its -1/N dragged
// one vertex on. Then the free case: the same pair alone on the surface, the field placing chi itself, and
// the -1/N dragged back.
void timeSingularityEdits(Designer& designer, int r, Samples& s) {
  const MeshTopology& t = designer.topology();
  const int32_t nV = t.numVertices, symmetry = designer.symmetry();
  const int32_t chi = t.boundaryLoops.empty() ? t.eulerCharacteristic() : 0;
  std::set<int32_t> used;
  std::vector<int32_t> background;
  const int32_t count = std::abs(chi) * symmetry;
  const double index = 1.0 / symmetry;
  designer.clearConstraints();
  for (int32_t k = 0; k < count; ++k) {
    const int32_t start = static_cast<int32_t>((int64_t(k) * nV / std::max(count, 1) + r * 7919) % nV);
    const int32_t v = freeVertex(designer, start, used, index);
    if (v < 0) return;  // too few interior vertices to prescribe
    used.insert(v);
    background.push_back(v);
  }
  const int32_t plus = freeVertex(designer, (r * 104729 + nV / 3) % nV, used, index);
  if (plus >= 0) used.insert(plus);
  const int32_t minus = plus < 0 ? -1 : freeVertex(designer, (r * 7919 + 2 * nV / 3) % nV, used, index);
  if (minus >= 0) used.insert(minus);
  const int32_t next = minus < 0 ? -1 : freeNeighbour(designer, minus, used, index);
  if (next < 0) return;  // no room for a pair (a mesh that is nearly all boundary)
  for (const int32_t v : background) designer.addSingularity(v, chi > 0 ? index : -index);
  designer.solve();
  const int64_t factorizationsBefore = designer.stats().factorizations;
  int32_t id = 0;
  s.singularityPlace.push_back(timeMs([&] {
    designer.addSingularity(plus, index);
    id = designer.addSingularity(minus, -index);
    designer.solve();  // with the read-outs, as the page gets them
  }));
  s.singularityMove.push_back(timeMs([&] {
    designer.moveSingularity(id, next);
    designer.solve();
  }));
  s.singularityFactorizations += designer.stats().factorizations - factorizationsBefore;
  s.singularityMode = designer.stats().singularityMode;
  designer.clearConstraints();
  designer.addSingularity(plus, index);
  id = designer.addSingularity(next, -index);
  designer.solve();
  s.singularityFreeMove.push_back(timeMs([&] {
    designer.moveSingularity(id, minus);
    designer.solve();
  }));
  designer.clearConstraints();
}

void runRepeat(Designer& designer, int r, bool metis, bool scaling, Samples& s) {
  const int32_t nF = designer.mesh().numFaces();
  designer.clearConstraints();
  // A fresh factored system: the designer would otherwise reuse the previous repeat's ordering.
  designer.setMetisOrdering(metis);
  designer.factor();
  s.analyze.push_back(designer.stats().analyzeMs);
  s.dissection.push_back(designer.stats().dissectionMs);
  s.factor.push_back(designer.stats().factorMs);
  s.convert.push_back(designer.stats().convertMs);
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
  s.factorGroups = designer.stats().factorGroups;
  if (!scaling) timeSingularityEdits(designer, r, s);
}

// The median of the exact placing and moving edits together: what one singularity edit costs the page.
double singularityEditMedian(const Samples& s) {
  std::vector<double> edits = s.singularityPlace;
  edits.insert(edits.end(), s.singularityMove.begin(), s.singularityMove.end());
  return median(edits);
}

nlohmann::json summary(const Samples& s, bool metis) {
  return {{"nnzPerRowM", s.nnzPerRowM},
          {"nnzPerRowL", s.nnzPerRowL},
          {"analyzeMs", median(s.analyze)},
          {"dissectionMs", median(s.dissection)},
          {"factorMs", median(s.factor)},
          {"convertMs", median(s.convert)},
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
          {"singularityEditMs", singularityEditMedian(s)},
          {"singularityPlaceMs", median(s.singularityPlace)},
          {"singularityMoveMs", median(s.singularityMove)},
          {"singularityFactorizations", s.singularityFactorizations},
          {"singularityMode", s.singularityMode},
          {"singularityFreeMoveMs", median(s.singularityFreeMove)},
          {"ordering", metis ? "metis" : "amd"},
          {"factorKind", s.factorKind},
          {"factorGroups", s.factorGroups}};
}

// A source and a stroke solved: the field the factorization on threads is checked by.
std::vector<double> checkField(Designer& d, bool metis) {
  d.clearConstraints();
  d.setMetisOrdering(metis);
  d.addSource(d.mesh().triangles[0], 1.0);
  d.addStroke(stripStroke(d.mesh(), d.topology(), 7, 50), 1.0, 1.0);
  d.solve();
  return d.oneForm();
}

// max |a - b| / max |b|.
double relativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0, scale = 0;
  for (size_t e = 0; e < b.size(); ++e) {
    diff = std::max(diff, std::abs(a[e] - b[e]));
    scale = std::max(scale, std::abs(b[e]));
  }
  return scale > 0 ? diff / scale : diff;
}

// The field on the designer's threads against the field on one, through the session's own solve (its kernel
// shift and refinement included), and, for scale, the serial field with the other ordering against it: how
// far a mere change in the order of the sums moves this system's field.
nlohmann::json parallelFieldDifference(Designer& designer, bool metis) {
  const std::vector<double> threaded = checkField(designer, metis);
  Designer serial(designer.mesh());
  serial.setSolverThreads(1);
  const std::vector<double> one = checkField(serial, metis);
  const std::vector<double> otherOrdering = checkField(serial, !metis);
  return {{"parallelFieldDifference", relativeDifference(threaded, one)},
          {"orderingFieldDifference", relativeDifference(otherOrdering, one)}};
}

// A single-edge update repeated in a loop, as a session's edits follow each other (updateMs times the first
// of a repeat, after a factorization and a solve): the median of the designer's own updateMs.
double steadyUpdateMs(Designer& designer) {
  designer.clearConstraints();
  designer.addSource(designer.mesh().triangles[0], 1.0);
  designer.solve();
  const int32_t nF = designer.mesh().numFaces();
  std::vector<double> updates;
  for (int r = 0; r < 51; ++r) {
    const int32_t face = (r * 7919 + 13) % nF;
    const int32_t id = designer.addEdge(designer.mesh().triangles[3 * face],
                                        designer.mesh().triangles[3 * face + 1], 0.1, 1.0);
    updates.push_back(designer.stats().updateMs);
    designer.remove(id);
  }
  designer.clearConstraints();
  return median(updates);
}

// The base matrix, its kernel shifted by 1e-8 of its mean diagonal (as the session's factor shifts it).
SparseMatrix shiftedBase(Designer& designer) {
  SparseMatrix A = designer.baseMatrix();
  SparseMatrix identity(A.rows(), A.cols());
  identity.setIdentity();
  A += (1e-8 * A.diagonal().mean()) * identity;
  return A;
}

}  // namespace

nlohmann::json runBench(const std::string& meshPath, int repeat, double gamma,
                        const std::vector<bool>& orderings, int threads, int symmetry, bool scaling) {
  Designer designer(loadMesh(meshPath));
  designer.setGamma(gamma);
  designer.setSymmetry(symmetry);
  if (threads > 0) designer.setSolverThreads(threads);
  std::vector<Samples> samples(orderings.size());
  // Orderings interleaved repeat by repeat, so that their ratios see the same machine state.
  for (int r = 0; r < repeat; ++r)
    for (size_t o = 0; o < orderings.size(); ++o) runRepeat(designer, r, orderings[o], scaling, samples[o]);
  nlohmann::json out = {{"mesh", meshPath},     {"edges", designer.edgeVertices().size() / 2},
                        {"repeat", repeat},     {"gamma", gamma},
                        {"symmetry", symmetry}, {"threads", designer.solverThreads()},
                        {"scaling", scaling}};
  if (designer.solverThreads() > 1 && symmetry == 1 && !scaling)
    out.update(parallelFieldDifference(designer, orderings[0]));
  if (symmetry == 1) {
    out["steadyUpdateMs"] = steadyUpdateMs(designer);
    if (!scaling) out.update(cholmodBaseline(shiftedBase(designer), 15));
  }
  if (orderings.size() == 1) {
    out.update(summary(samples[0], orderings[0]));
    return out;
  }
  for (size_t o = 0; o < orderings.size(); ++o)
    out[orderings[o] ? "metis" : "amd"] = summary(samples[o], orderings[o]);
  return out;
}

}  // namespace tvf
