#include "quad/quad_remesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/input_error.h"
#include "common/stopwatch.h"
#include "field/singularities.h"
#include "mesh/feature_edges.h"
#include "mesh/mesh_geometry.h"
#include "quad/cross_field_cut.h"
#include "quad/quad_extraction.h"
#include "quad/seamless_parametrization.h"

namespace tvf {
namespace {

constexpr double kMostQuads = 4e6;

double chosenEdgeLength(const MeshGeometry& g, const QuadRemeshOptions& o) {
  if (o.edgeLength != 0) {
    if (!(o.edgeLength > 0) || !std::isfinite(o.edgeLength))
      throw InputError("quad mesh: the edge length must be a positive number");
    if (g.totalArea / (o.edgeLength * o.edgeLength) > kMostQuads)
      throw InputError("quad mesh: an edge length of " + std::to_string(o.edgeLength) +
                       " would make more than 4 million quads");
    return o.edgeLength;
  }
  if (o.targetQuads <= 0) throw InputError("quad mesh: give an edge length or a number of quads");
  if (o.targetQuads > kMostQuads) throw InputError("quad mesh: at most 4 million quads");
  return std::sqrt(g.totalArea / static_cast<double>(o.targetQuads));
}

void checkInputs(const MeshTopology& t, const std::vector<double>& faceDirections, int symmetry) {
  if (symmetry != 4)
    throw InputError("Quad meshes need a cross field (symmetry 4); this field has symmetry " +
                     std::to_string(symmetry));
  if (faceDirections.size() != 3 * static_cast<std::size_t>(t.numFaces))
    throw InputError("quad mesh: expected 3 numbers per face for the field's directions");
  for (double x : faceDirections)
    if (!std::isfinite(x)) throw InputError("quad mesh: the field's directions are not finite numbers");
}

// Folded triangles (their (u, v) not counter-clockwise) and their neighbours weigh more.
void stiffenFolds(const MeshTopology& t, const SeamlessParametrization& p, std::vector<double>& weight) {
  std::vector<uint8_t> folded(t.numFaces, 0);
  for (int32_t f = 0; f < t.numFaces; ++f) folded[f] = !(uvTwiceArea(p.cornerUV, f) > 0);
  for (int32_t f = 0; f < t.numFaces; ++f) {
    if (!folded[f]) continue;
    weight[f] *= 8;
    for (int c = 0; c < 3; ++c) {
      const int32_t h = t.otherFace(t.edgeOf(f, c), f);
      if (h >= 0 && !folded[h]) weight[h] *= 2;
    }
  }
}

std::vector<int32_t> featureEdgeIndices(const MeshTopology& t, const std::vector<int32_t>& pairs) {
  if (pairs.size() % 2) throw InputError("quad mesh: feature edges come as vertex pairs");
  std::vector<int32_t> edges;
  for (std::size_t k = 0; k < pairs.size(); k += 2) {
    const int32_t a = pairs[k], b = pairs[k + 1];
    const int32_t e = a >= 0 && b >= 0 && a < t.numVertices && b < t.numVertices ? findEdge(t, a, b) : -1;
    if (e < 0)
      throw InputError("quad mesh: the feature pair (" + std::to_string(a) + ", " + std::to_string(b) +
                       ") is not an edge of the mesh");
    edges.push_back(e);
  }
  return edges;
}

// The feature curves (mesh/feature_edges.h) at least `shortest` long. A shorter one (a stray sharp edge on an
// organic model, a notch) held to an integer line would bend the grid round it by up to half a quad.
std::vector<FeatureCurve> followedCurves(const SurfaceMesh& mesh, const MeshTopology& t,
                                         const std::vector<int32_t>& edges, double shortest) {
  std::vector<int32_t> sorted = edges;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  std::vector<FeatureCurve> out;
  for (FeatureCurve& curve : featureCurves(t, sorted)) {
    double length = 0;
    for (int32_t e : curve.edges) length += edgeVector(mesh, t, e).norm();
    if (length >= shortest) out.push_back(std::move(curve));
  }
  return out;
}

std::vector<int32_t> keptEdges(const std::vector<FeatureCurve>& curves, const std::vector<uint8_t>& kept) {
  std::vector<int32_t> out;
  for (std::size_t c = 0; c < curves.size(); ++c)
    if (kept[c]) out.insert(out.end(), curves[c].edges.begin(), curves[c].edges.end());
  return out;
}

// Features closer together than a quad cannot all be lines of the grid (a tube's creases at a coarse size):
// where the parametrization still folds, the curves that touch a folded triangle are let go. Only when the
// features are what folds it (half the folded triangles or more touch a kept curve): the folds of a field
// with singularities closer than a quad (a scan's at a 35-degree feature angle: armadillo-sub2's 647) would
// stay, and each pass is a whole parametrization again. Returns how many were let go.
int32_t releaseCurvesNearFolds(const SurfaceMesh& mesh, const MeshTopology& t,
                               const SeamlessParametrization& p, const std::vector<FeatureCurve>& curves,
                               std::vector<uint8_t>& kept) {
  std::vector<uint8_t> onCurve(t.numVertices, 0), nearFold(t.numVertices, 0);
  for (std::size_t c = 0; c < curves.size(); ++c)
    if (kept[c])
      for (int32_t e : curves[c].edges)
        onCurve[t.edgeVertices[2 * e]] = onCurve[t.edgeVertices[2 * e + 1]] = 1;
  int32_t folds = 0, foldsByCurves = 0;
  for (int32_t f = 0; f < t.numFaces; ++f) {
    if (uvTwiceArea(p.cornerUV, f) > 0) continue;
    ++folds;
    const int32_t* v = &mesh.triangles[3 * f];
    foldsByCurves += onCurve[v[0]] || onCurve[v[1]] || onCurve[v[2]];
    for (int c = 0; c < 3; ++c) nearFold[v[c]] = 1;
  }
  if (2 * foldsByCurves < folds) return 0;
  int32_t released = 0;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    if (!kept[c]) continue;
    for (int32_t e : curves[c].edges)
      if (nearFold[t.edgeVertices[2 * e]] || nearFold[t.edgeVertices[2 * e + 1]]) {
        kept[c] = 0, ++released;
        break;
      }
  }
  return released;
}

// One pass: the cut with the curves kept, and its parametrization with the counts the statistics report.
struct Pass {
  CrossFieldCut cut;
  SeamlessParametrization param;
  int32_t integerUnknowns = 0, unenforcedConditions = 0, roundingSolves = 0, stiffenings = 0;
  int32_t releasedCurves = 0;  // let go before this pass
};

// Stiffening (after Bommes et al. 2009, Sec. 4.3): where a solve folds triangles over, their terms weigh more
// and it is solved again, up to kStiffenings times. The integers rounded by the first solve are kept: each
// further solve is one factorization (on bunny00 the folds went 26, 20, 3, 0; rounding again each time went
// 26, 19, 12, 4, 10, 1, 1 at twice the cost). Progress goes from `from` to `to`.
void parametrize(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g, double edgeLength,
                 double from, double to, const RemeshProgress& progress, Pass& pass) {
  constexpr int kStiffenings = 8;
  const SeamlessSystem system(t, pass.cut);
  pass.integerUnknowns = system.integerUnknowns();
  pass.unenforcedConditions = system.unenforcedConditions();
  std::vector<double> weight(t.numFaces, 1.0);
  SeamlessParametrization param, best;
  for (int round = 0; round <= kStiffenings; ++round) {
    bool stopped = false;
    const double span = (to - from) / (kStiffenings + 1), at = from + span * round;
    param = system.solve(mesh, g, edgeLength, weight, round > 0 ? best.integers : std::vector<double>{},
                         [&](double fraction) {
                           stopped = progress && !progress("parametrizing", at + span * fraction);
                           return !stopped;
                         });
    if (stopped) throw RemeshCancelled();
    if (round == 0) pass.roundingSolves = param.roundingSteps;
    // Folds can wander as the weights change: the solve with the fewest is the one kept.
    const bool better = round == 0 || param.flippedFaces < best.flippedFaces;
    if (better) best = std::move(param), pass.stiffenings = round;
    if (best.flippedFaces == 0 || round == kStiffenings) break;
    stiffenFolds(t, better ? best : param, weight);
  }
  pass.param = std::move(best);
}

}  // namespace

QuadRemeshResult quadRemesh(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                            const std::vector<double>& faceDirections, int symmetry,
                            const QuadRemeshOptions& options, const RemeshProgress& progress) {
  const Clock::time_point start = Clock::now();
  checkInputs(t, faceDirections, symmetry);
  const std::vector<int32_t> features = featureEdgeIndices(t, options.featureEdges);
  QuadRemeshResult out;
  out.edgeLength = chosenEdgeLength(g, options);
  auto report = [&](const char* stage, double fraction) {
    if (progress && !progress(stage, fraction)) throw RemeshCancelled();
  };
  // The features are followed where they can be: a first parametrization with every curve long enough, and
  // up to two more with those near its folds let go (boundary edges are always followed).
  std::vector<int32_t> interiorFeatures;  // the boundary is followed anyway, and never let go
  for (int32_t e : features)
    if (!t.isBoundaryEdge[e]) interiorFeatures.push_back(e);
  const std::vector<FeatureCurve> curves = followedCurves(mesh, t, interiorFeatures, out.edgeLength);
  std::vector<uint8_t> kept(curves.size(), 1);
  constexpr double kPassProgress[] = {0.05, 0.45, 0.65, 0.75};
  // Each pass is kept when it folds less than the best before it (letting curves go need not help).
  Pass best, pass;
  for (int k = 0;; ++k) {
    report("cutting", kPassProgress[k]);
    Clock::time_point stage = Clock::now();
    pass.cut = cutCrossField(mesh, t, g, faceDirections, keptEdges(curves, kept));
    out.cutMs += msSince(stage);
    stage = Clock::now();
    parametrize(mesh, t, g, out.edgeLength, kPassProgress[k], kPassProgress[k + 1], progress, pass);
    out.parametrizeMs += msSince(stage);
    const int32_t releasedBefore = pass.releasedCurves;
    const int32_t more =
        pass.param.flippedFaces > 0 && k < 2 ? releaseCurvesNearFolds(mesh, t, pass.param, curves, kept) : 0;
    if (k == 0 || pass.param.flippedFaces < best.param.flippedFaces) best = std::move(pass);
    if (more == 0) break;
    pass = Pass{};
    pass.releasedCurves = releasedBefore + more;
  }
  out.featureCurves = static_cast<int32_t>(curves.size());
  out.releasedFeatureCurves = best.releasedCurves;
  out.integerUnknowns = best.integerUnknowns;
  out.unenforcedConditions = best.unenforcedConditions;
  out.roundingSolves = best.roundingSolves;
  out.stiffenings = best.stiffenings;
  out.cones = best.cut.cones;
  out.cutEdges = best.cut.cutEdges;
  out.flippedTriangles = best.param.flippedFaces;
  const CrossFieldCut& cut = best.cut;
  const SeamlessParametrization& param = best.param;

  report("extracting", 0.75);
  Clock::time_point stage = Clock::now();
  QuadExtraction extraction = extractQuads(mesh, t, cut, param);
  out.failedTraces = extraction.failedTraces;
  out.openLoops = extraction.openLoops;
  out.filledHoles = extraction.filledHoles;
  out.splitPolygons = extraction.splitPolygons;
  out.mesh = std::move(extraction.mesh);
  out.extractMs = msSince(stage);
  if (out.mesh.numFaces() == 0)
    throw InputError("quad mesh: no quad could be made at this edge length; try a smaller one");

  report("measuring", 0.9);
  stage = Clock::now();
  const std::vector<Singularity> singularities = findSingularities(mesh, t, g, faceDirections, symmetry);
  out.stats = measureQuadMesh(out.mesh, mesh, g, faceDirections, symmetry, singularities, out.edgeLength);
  out.measureMs = msSince(stage);
  out.totalMs = msSince(start);
  report("done", 1.0);
  return out;
}

}  // namespace tvf
