// SPDX-License-Identifier: GPL-2.0-or-later
//
// embind bindings of the field-design core: the `Designer` class the page (web/core-client.js) drives.
//
// Conventions (the front end relies on them):
// * Nothing throws into JS. Calls that can fail return '' on success or the error message (string results),
//   -1 plus lastError() (constraint ids), or false plus lastError() (remove/setWeight/setStrength).
// * Array read-outs are typed_memory_view()s into wasm memory, not copies: they are valid until the next
//   mutating call (load, solve, ...) or memory growth; copy them (TypedArray.from / slice) to keep them.
// * Loads are transactional: loadModel (and loadMesh) parse, check, configure, factor and solve the new model
//   in a Designer of its own and replace the current one only when every step succeeded; on any error (a
//   broken file, a mesh that cannot be factored, a factor that would not fit in memory) the previous mesh,
//   constraints and field stay as they were, fully usable.
// * Before each factorization the designer is told how much memory is left in the 4 GB address space, so an
//   oversized factor is refused from CHOLMOD's symbolic analysis instead of failing half-way (or trapping).
//
// Besides the class, the module exports warmUp(): a small factor/update/solve cycle on a generated sphere that
// lets V8 tier the hot functions up (Liftoff -> TurboFan) before the first large factorization; see
// wasm/bench.mjs for the measured effect.
#include <emscripten/bind.h>
#include <emscripten/heap.h>
#include <malloc.h>
#include <emscripten/val.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/thread_team.h"
#include "design/design_document.h"
#include "design/design_stripes.h"
#include "design/designer.h"
#include "design/mesh_info.h"
#include "field/hodge_decomposition.h"
#include "field/whitney_reconstruction.h"
#include "io/mesh_io.h"
#include "mesh/face_adjacency.h"
#include "mesh/icosphere.h"
#include "solver/factor_memory.h"

namespace {

using emscripten::val;

// Wraps a call: runs `f`, turns any exception into its message. Returns true on success.
template <typename F>
bool attempt(std::string& error, F&& f) {
  try {
    f();
    error.clear();
    return true;
  } catch (const std::bad_alloc&) {
    error = "out of memory";
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "unknown error in the core";
  } catch (...) {
    error = "unknown error in the core";
  }
  return false;
}

bool parseFormat(std::string name, const uint8_t* data, std::size_t size, tvf::MeshFormat& out) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (!name.empty() && name[0] == '.') name.erase(0, 1);
  if (name.empty()) {
    out = tvf::formatFromBytes(data, size);
    return true;
  }
  static const std::map<std::string, tvf::MeshFormat> kFormats = {
      {"glb", tvf::MeshFormat::Glb}, {"gltf", tvf::MeshFormat::Gltf}, {"obj", tvf::MeshFormat::Obj},
      {"off", tvf::MeshFormat::Off}, {"ply", tvf::MeshFormat::Ply}};
  const auto it = kFormats.find(name);
  if (it == kFormats.end()) return false;
  out = it->second;
  return true;
}

// A JS number that must be an int32 index (face, vertex, id); embind would silently truncate 1.5 or NaN.
// The number is printed as JS would (1e12 as 1000000000000), never after narrowing.
int32_t toIndex(double x, const char* what) {
  if (!std::isfinite(x) || x != std::floor(x) || x < -2147483648.0 || x > 2147483647.0) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", x);
    throw tvf::InputError(std::string(what) + " must be an integer index (got " +
                          (std::isfinite(x) ? std::string(text) : std::string("a non-finite number")) + ")");
  }
  return static_cast<int32_t>(x);
}

// What the next factorization may use: the address space left above what is allocated now, less a margin
// for the solve's vectors and the read-outs.
double availableHeapBytes() {
  constexpr double kMargin = 64.0 * 1024 * 1024;
  const double heapMax = static_cast<double>(emscripten_get_heap_max());
  const double inUse = static_cast<double>(mallinfo().uordblks);
  return std::max(1.0, heapMax - inUse - kMargin);
}

template <typename T>
val view(const std::vector<T>& v) {
  return val(emscripten::typed_memory_view(v.size(), v.data()));
}

// A Float64Array of its own (a copy out of wasm memory, made before anything else can run).
val copyOf(const double* data, std::size_t size) {
  return val::global("Float64Array").new_(val(emscripten::typed_memory_view(size, data)));
}
val copyOf(const std::vector<double>& v) { return copyOf(v.data(), v.size()); }
val copyOf(const std::vector<int32_t>& v) {
  return val::global("Int32Array").new_(val(emscripten::typed_memory_view(v.size(), v.data())));
}
val copyOf(const Eigen::VectorXd& v) { return copyOf(v.data(), static_cast<std::size_t>(v.size())); }

// Vertex pairs from a flat list of numbers [a, b, a, b, ...] (feature edges to add or remove).
std::vector<std::array<int32_t, 2>> vertexPairs(const val& flat, const char* what) {
  const std::vector<double> v = emscripten::convertJSArrayToNumberVector<double>(flat);
  if (v.size() % 2 != 0)
    throw tvf::InputError(std::string(what) + ": expected 2 vertices per edge, got " + std::to_string(v.size()) +
                          " numbers");
  std::vector<std::array<int32_t, 2>> out(v.size() / 2);
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = {toIndex(v[2 * k], what), toIndex(v[2 * k + 1], what)};
  return out;
}

nlohmann::json pairsJson(const std::vector<std::array<int32_t, 2>>& pairs) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : pairs) out.push_back({p[0], p[1]});
  return out;
}

class DesignerBinding {
 public:
  // format: 'glb' | 'gltf' | 'obj' | 'off' | 'ply' | '' (sniffed from the bytes).
  std::string loadMesh(const val& bytes, const std::string& format) {
    std::string error;
    attempt(error, [&] {
      designer_ = prepareModel(bytes, format, "", "", nullptr, nullptr);
      ++modelSerial_;
    });
    lastError_ = error;
    return error;
  }

  // The whole model change as one transaction: mesh, then settings (JSON {"boundary", "gamma", "symmetry",
  // "curvatureAlignment", "featureAngle"}; '' for the defaults), then an autosaved design (JSON document; ''
  // for none), then factor and solve. Settings or a design the new mesh cannot take are dropped and reported
  // (settingsError, restoreError) without failing the load; a mesh that cannot be read, checked, factored or
  // solved fails it. Returns JSON:
  // {"ok": true, "settingsError": string|null, "restoreError": string|null} or {"ok": false, "error": string}.
  std::string loadModel(const val& bytes, const std::string& format, const std::string& settings,
                        const std::string& design) {
    std::string error, settingsError, restoreError;
    const bool ok = attempt(error, [&] {
      designer_ = prepareModel(bytes, format, settings, design, &settingsError, &restoreError);
      ++modelSerial_;
    });
    lastError_ = error;
    return loadResult(ok, error, settingsError, restoreError);
  }

  // loadModel in steps, for big meshes (web/core/open-steps.js): readModel parses the file into the next
  // model's mesh ({"ok", "vertices", "faces"} or {"ok": false, "error"}) and parsedPositions/parsedTriangles
  // view it, so a preview can start on it while openParsed checks and configures it aside (seconds less than the
  // factorization); its mesh and design can then be read (pending*) while commitModel factors and solves it and
  // makes it current. The same transaction: until commitModel succeeds the current model is untouched; a failed
  // step drops what it was given.
  std::string readModel(const val& bytes, const std::string& format) {
    std::string error;
    pending_.reset();
    parsed_.reset();
    if (attempt(error, [&] { parsed_ = std::make_unique<tvf::SurfaceMesh>(parseMesh(bytes, format)); }))
      return nlohmann::json{{"ok", true}, {"vertices", parsed_->numVertices()}, {"faces", parsed_->numFaces()}}.dump();
    lastError_ = error;
    return nlohmann::json{{"ok", false}, {"error", error}}.dump();
  }
  val parsedPositions() const { return parsed_ ? view(parsed_->positions) : view(emptyD_); }
  val parsedTriangles() const { return parsed_ ? view(parsed_->triangles) : view(emptyI_); }
  std::string openParsed(const std::string& settings, const std::string& design) {
    std::string error, settingsError, restoreError;
    pending_.reset();
    const bool ok = attempt(error, [&] {
      if (!parsed_) throw tvf::InputError("no model has been read to open");
      tvf::SurfaceMesh mesh = std::move(*parsed_);
      parsed_.reset();
      pending_ = configured(std::move(mesh), settings, design, &settingsError, &pendingRestored_);
    });
    restoreError = pendingRestored_.error;
    lastError_ = error;
    return loadResult(ok, error, settingsError, restoreError);
  }

  std::string commitModel() {
    std::string error;
    if (!pending_) return nlohmann::json{{"ok", false}, {"error", "no model is open to commit"}}.dump();
    if (attempt(error, [&] {
          // The model being replaced lets its factor go first (its design and field stay): a big model opened
          // over itself otherwise factors beside a factor as big as its own in the same heap. Should the commit
          // fail, the model kept factors again at its next solve. The same mesh opened again (same hash and N)
          // gets the old factor's largest blocks for its own (solver/factor_memory.h); another model, the room.
          if (designer_) {
            if (designer_->meshHash() == pending_->meshHash() && designer_->symmetry() == pending_->symmetry())
              tvf::factor_memory::keepWhatIsFreed();
            designer_->releaseFactors();
          }
          solvePrepared(*pending_, pendingRestored_);
          designer_ = std::move(pending_);
          ++modelSerial_;
        })) {
      pending_.reset();
      lastError_.clear();
      const std::string& r = pendingRestored_.error;
      return nlohmann::json{{"ok", true}, {"restoreError", r.empty() ? nlohmann::json() : nlohmann::json(r)}}.dump();
    }
    pending_.reset();
    lastError_ = error;
    return nlohmann::json{{"ok", false}, {"error", error}}.dump();
  }
  std::string pendingInfoJson() const {
    return pending_ ? tvf::meshInfoJson(*pending_).dump() : "null";
  }
  std::string pendingDesignJson() const {
    return json([&] { return pending_ ? tvf::designDocument(*pending_) : nlohmann::json(); });
  }
  val pendingPositions() const { return pending_ ? view(pending_->mesh().positions) : view(emptyD_); }
  val pendingTriangles() const { return pending_ ? view(pending_->mesh().triangles) : view(emptyI_); }
  val pendingEdges() const { return pending_ ? view(pending_->edgeVertices()) : view(emptyI_); }
  val pendingCornerUVs() const { return pending_ ? view(pending_->mesh().cornerUVs) : view(emptyF_); }
  // The pending mesh's face adjacency for the page's picking (mesh/face_adjacency.h), in arrays of its own that
  // the worker hands over: {neighbour, vertexFaceStart, vertexFaces, normals}, or null.
  val pendingFaceAdjacency() const {
    if (!pending_) return val::null();
    const tvf::SurfaceMesh& mesh = pending_->mesh();
    const tvf::VertexFaces round = tvf::vertexFaces(mesh, pending_->topology().numVertices);
    val out = val::object();
    out.set("neighbour", copyOf(tvf::halfEdgeTwins(pending_->topology())));
    out.set("vertexFaceStart", copyOf(round.start));
    out.set("vertexFaces", copyOf(round.faces));
    out.set("normals", copyOf(tvf::pageFaceNormals(pending_->geometry())));
    return out;
  }

  // The fill-reducing ordering kept per mesh by the page (web/core/worker/ordering-cache.js): the pending
  // model's key (its mesh hash and field symmetry), an ordering kept for it adopted before commitModel factors
  // (FactoredSystem::adoptOrdering; a stale one is found so at factorization), and the current model's own:
  // keptOrderingJson() {n, pattern, metis, dissection} with keptOrderingPerm() viewing the permutation.
  std::string pendingOrderingKey() const {
    if (!pending_) return "";
    return pendingMeshHash() + "-n" + std::to_string(pending_->symmetry());
  }
  // The pending mesh's hash (its float positions' bits and its triangles), in hex: the key of what the worker
  // keeps per mesh (web/core/worker/picking-cache.js).
  std::string pendingMeshHash() const {
    if (!pending_) return "";
    char key[20];
    std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(pending_->meshHash()));
    return key;
  }
  // symbolic: null, or the ordering's supernodal symbolic factor as keptSymbolicBytes() gives it
  // (FactoredSystem::adoptOrdering checks it against the matrix before it is used).
  bool adoptPendingOrdering(const val& perm, const std::string& patternHex, bool metis, bool dissection,
                            const val& symbolic) {
    if (!pending_) return false;
    tvf::KeptOrdering k;
    k.perm = emscripten::convertJSArrayToNumberVector<int32_t>(perm);
    k.pattern = std::strtoull(patternHex.c_str(), nullptr, 16);
    k.ordering = metis ? tvf::FillOrdering::Metis : tvf::FillOrdering::Amd;
    k.dissection = dissection;
    if (!symbolic.isNull() && !symbolic.isUndefined()) {
      const std::vector<uint8_t> bytes = emscripten::convertJSArrayToNumberVector<uint8_t>(symbolic);
      k.symbolic = tvf::symbolicFromBytes(bytes.data(), bytes.size());
    }
    return pending_->adoptFieldOrdering(std::move(k));
  }
  // The pending model's matrix assembled ahead of commitModel (Designer::prepareSystem); a failure is left for
  // commitModel to meet and report.
  void preparePendingSystem() {
    std::string error;
    if (pending_) attempt(error, [&] { pending_->prepareSystem(); });
  }
  // Whether the pending model's analysis is kept for keptOrderingJson (Designer::keepFieldSymbolic).
  void keepPendingSymbolic(bool keep) {
    if (pending_) pending_->keepFieldSymbolic(keep);
  }
  // n = 0: nothing the page's cache lacks (Designer::fieldOrderingIsNew), and nothing copied out.
  std::string keptOrderingJson() {
    kept_ = designer_ && designer_->fieldOrderingIsNew() ? designer_->fieldOrdering() : tvf::KeptOrdering{};
    symbolicBytes_ = tvf::symbolicBytes(kept_.symbolic);
    kept_.symbolic = tvf::KeptSymbolic();
    char pattern[20];
    std::snprintf(pattern, sizeof pattern, "%016llx", static_cast<unsigned long long>(kept_.pattern));
    return nlohmann::json{{"n", kept_.perm.size()},
                          {"pattern", pattern},
                          {"metis", kept_.ordering == tvf::FillOrdering::Metis},
                          {"dissection", kept_.dissection},
                          {"symbolic", !symbolicBytes_.empty()},
                          {"reused", designer_ && designer_->stats().analysisReused}}
        .dump();
  }
  val keptOrderingPerm() const { return view(kept_.perm); }
  // Its symbolic factor's bytes (tvf::symbolicBytes), or none.
  val keptSymbolicBytes() const { return view(symbolicBytes_); }
  // What keptOrderingJson copied, and the current model's copy of its symbolic factor, let go.
  void releaseKeptOrdering() {
    kept_ = tvf::KeptOrdering{};
    std::vector<uint8_t>().swap(symbolicBytes_);
    if (designer_) designer_->keepFieldSymbolic(false);
  }

  // bytes <= 0: the address space left in wasm memory (the default); otherwise a fixed limit, for tests.
  std::string setFactorMemoryLimit(double bytes) {
    return run([&] {
      if (!std::isfinite(bytes)) throw tvf::InputError("the factor memory limit must be a finite number");
      memoryLimit_ = std::max(0.0, bytes);
      if (designer_) fitMemory(*designer_);
    });
  }

  std::string infoJson() const {
    std::string out, error;
    if (!attempt(error, [&] { out = designer_ ? tvf::meshInfoJson(*designer_).dump() : tvf::meshInfoJson(tvf::SurfaceMesh{}).dump(); }))
      return "null";
    return out;
  }

  std::string setBoundaryJson(const std::string& text) {
    return run([&] { need().setBoundary(tvf::boundaryFromJson(nlohmann::json::parse(text))); });
  }
  std::string setGamma(double gamma) { return run([&] { need().setGamma(gamma); }); }
  double gamma() const { return designer_ ? designer_->gamma() : 0.0; }
  // N of the field (1 vector, 2 line, 4 cross; up to 6): refused, naming them, while the design holds
  // sources, sinks, vortices or edge values; the next solve factors the new system.
  std::string setSymmetry(int symmetry) { return run([&] { need().setSymmetry(symmetry); }); }
  int symmetry() const { return designer_ ? designer_->symmetry() : 1; }
  std::string setCurvatureAlignment(double s) { return run([&] { need().setCurvatureAlignment(s); }); }
  double curvatureAlignment() const { return designer_ ? designer_->curvatureAlignment() : 0.0; }
  // METIS nested dissection (the default) or AMD; the next factorization orders again.
  std::string setMetisOrdering(bool metis) { return run([&] { need().setMetisOrdering(metis); }); }
  // Whether every model from here on holds an added constraint's update beside its factor until
  // applyDeferredUpdates() (tvf::Designer::setDeferredUpdates): the worker replies with the field first.
  std::string setDeferredUpdates(bool defer) {
    return run([&] {
      deferUpdates_ = defer;
      if (designer_) designer_->setDeferredUpdates(defer);
    });
  }
  std::string applyDeferredUpdates() {
    return run([&] {
      if (designer_) designer_->applyDeferredUpdates();
    });
  }
  // Threads of the backward substitution (1 .. solverThreadsAvailable()); the next solve refactors.
  std::string setSolverThreads(int threads) {
    return run([&] { need().setSolverThreads(threads); });
  }
  int solverThreads() const {
    return designer_ ? designer_->solverThreads() : tvf::ThreadTeam::usefulParts();
  }
  std::string factor() {
    return run([&] {
      fitMemory(need());
      need().factor();
    });
  }
  std::string solve() {
    return run([&] {
      fitMemory(need());
      need().solve();
    });
  }

  // flat: [face, a, b, c, face, a, b, c, ...] (face indices as numbers).
  int addStroke(const val& flat, double strength, double weight) {
    return add([&] {
      const std::vector<double> v = emscripten::convertJSArrayToNumberVector<double>(flat);
      if (v.size() % 4 != 0) throw tvf::InputError("stroke: expected 4 numbers per point (face, a, b, c)");
      std::vector<tvf::SurfacePoint> points(v.size() / 4);
      for (std::size_t k = 0; k < points.size(); ++k) {
        points[k].face = toIndex(v[4 * k], "stroke point face");
        for (int c = 0; c < 3; ++c) points[k].bary[c] = v[4 * k + 1 + c];
      }
      return need().addStroke(points, strength, weight);
    });
  }
  int addVector(double face, double x, double y, double z, double weight) {
    return add([&] {
      const double u[3] = {x, y, z};
      return need().addVector(toIndex(face, "face"), u, weight);
    });
  }
  int addEdge(double i, double j, double value, double weight) {
    return add([&] { return need().addEdge(toIndex(i, "vertex i"), toIndex(j, "vertex j"), value, weight); });
  }
  int addSource(double v, double strength) {
    return add([&] { return need().addSource(toIndex(v, "vertex"), strength); });
  }
  int addSink(double v, double strength) {
    return add([&] { return need().addSink(toIndex(v, "vertex"), strength); });
  }
  int addVortex(double f, double strength) {
    return add([&] { return need().addVortex(toIndex(f, "face"), strength); });
  }
  // One constraint object of the design format, re-added exactly as saved (undo of a delete, redo); a
  // prescribed singularity as {"type": "singularity", "vertex", "index"}, as constraintJson() gives it.
  int addConstraintJson(const std::string& text) {
    return add([&] { return need().add(tvf::constraintFromJson(nlohmann::json::parse(text))); });
  }
  // A prescribed singularity: its id, or -1 with the core's reason in lastError() (a boundary vertex, an
  // index that is not a nonzero multiple of 1/N, a vertex that has one); the design is then unchanged.
  int addSingularity(double vertex, double index) {
    return add([&] { return need().addSingularity(toIndex(vertex, "singularity vertex"), index); });
  }
  // Keeps the id and the index; false with lastError() when refused.
  bool moveSingularity(double id, double vertex) {
    return ok([&] { need().moveSingularity(toIndex(id, "id"), toIndex(vertex, "singularity vertex")); });
  }
  // Feature edges: those whose dihedral angle exceeds `degrees` (0: none), plus `add`, minus `remove` (flat
  // vertex pairs [a, b, a, b, ...]); '' or the core's refusal (a pair that is not an edge, a bad angle), the
  // design then unchanged. The next solve factors the new system.
  std::string setFeatures(double degrees, const val& add, const val& remove) {
    return run([&] {
      const auto plus = vertexPairs(add, "feature edge to add");
      const auto minus = vertexPairs(remove, "feature edge to remove");
      need().setFeatures(degrees, plus, minus);
    });
  }
  double featureAngle() const { return designer_ ? designer_->featureAngle() : 0.0; }
  // true: the field has exactly the prescribed singularities, none when none are prescribed (a torus's cross
  // field without any); '' or the core's refusal, the design then unchanged.
  std::string setExactSingularities(bool exact) {
    return run([&] { need().setExactSingularities(exact); });
  }
  bool exactSingularities() const { return designer_ && designer_->exactSingularities(); }
  // {"angle", "add": [[a, b], ...], "remove": [[a, b], ...]}: the design's features as set.
  std::string featuresJson() const {
    return json([&] {
      const std::vector<std::array<int32_t, 2>> none;
      return nlohmann::json{{"angle", featureAngle()},
                            {"add", pairsJson(designer_ ? designer_->featureEdgesAdded() : none)},
                            {"remove", pairsJson(designer_ ? designer_->featureEdgesRemoved() : none)}};
    });
  }
  // The edges the field follows as features (indices into edges(), ascending): a view into wasm memory.
  val featureEdges() const { return designer_ ? view(designer_->featureEdges()) : view(emptyI_); }

  bool remove(double id) { return ok([&] { need().remove(toIndex(id, "id")); }); }
  bool setWeight(double id, double w) { return ok([&] { need().setWeight(toIndex(id, "id"), w); }); }
  bool setStrength(double id, double s) { return ok([&] { need().setStrength(toIndex(id, "id"), s); }); }
  bool clearConstraints() { return ok([&] { need().clearConstraints(); }); }
  std::string lastError() const { return lastError_; }
  bool hasMesh() const { return designer_ != nullptr; }

  // Views into wasm memory (no copies).
  val positions() const { return designer_ ? view(designer_->mesh().positions) : view(emptyD_); }
  val triangles() const { return designer_ ? view(designer_->mesh().triangles) : view(emptyI_); }
  val edges() const { return designer_ ? view(designer_->edgeVertices()) : view(emptyI_); }
  val oneForm() const { return designer_ ? view(designer_->oneForm()) : view(emptyD_); }
  val faceVectors() const { return designer_ ? view(designer_->faceVectors()) : view(emptyD_); }
  val vertexVectors() const { return designer_ ? view(designer_->vertexVectors()) : view(emptyD_); }
  val cornerUVs() const { return designer_ ? view(designer_->mesh().cornerUVs) : view(emptyF_); }
  // glTF: the welded vertex of every source vertex (the exporter keeps the model's layout with it).
  val sourceToWelded() const { return designer_ ? view(designer_->mesh().sourceToWelded) : view(emptyI_); }

  // The stripe pattern (design/design_stripes.h) of the field the page draws: vertexVectors, 3 per vertex (the
  // whole field or a Hodge part; null: the design's own). options: designStripeOptionsFromJson's JSON. '' or
  // the error. Kept per model, so that the next one starts from this one; read by the views below until then.
  // interrupted: null, or a function asked between the computation's steps; true abandons it (''; then
  // stripesInterrupted() is true and the last pattern stays).
  std::string computeStripes(const val& vertexVectors, const std::string& options, const val& interrupted) {
    stripesInterrupted_ = false;
    return run([&] {
      const tvf::Designer& d = need();
      if (stripesModel_ != modelSerial_) {
        stripes_.clear();
        stripesModel_ = modelSerial_;
      }
      tvf::DesignStripeOptions o = tvf::designStripeOptionsFromJson(options, d.symmetry());
      if (interrupted.typeOf().as<std::string>() == "function")
        o.interrupted = [&interrupted] { return interrupted().as<bool>(); };
      const std::vector<double> given =
          vertexVectors.isNull() || vertexVectors.isUndefined() ? std::vector<double>{}
                                   : emscripten::convertJSArrayToNumberVector<double>(vertexVectors);
      if (!given.empty() && given.size() != d.mesh().positions.size())
        throw tvf::InputError("stripes: expected 3 numbers per vertex of the model");
      const auto t0 = std::chrono::steady_clock::now();
      try {
        // The design's own field has its faces' too; a given one (a Hodge part) its vertices' alone.
        stripes_.compute(d.mesh(), d.topology(), d.geometry(), d.vertexNormals(), d.symmetry(),
                         given.empty() ? d.vertexVectors() : given, o,
                         given.empty() ? &d.faceVectors() : nullptr);
      } catch (const tvf::StripesInterrupted&) {
        stripesInterrupted_ = true;
      }
      stripesMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    });
  }
  bool stripesInterrupted() const { return stripesInterrupted_; }
  // families x 3 per face (family-major), radians; families per face (family-major).
  val stripeCornerPhase() const { return view(stripes_.pattern().cornerPhase); }
  val stripeBranchIndex() const { return view(stripes_.pattern().branchIndex); }
  std::string stripeStatsJson() const {
    const tvf::StripePattern& p = stripes_.pattern();
    return nlohmann::json{{"families", p.families},     {"profile", tvf::stripeProfileName(stripes_.profile())},
                          {"eigenvalue", p.eigenvalue}, {"residual", p.residual},
                          {"iterations", p.iterations}, {"factorMs", p.factorMs},
                          {"iterateMs", p.iterateMs},   {"analysisReused", p.analysisReused},
                          {"spacingMs", p.spacingMs},   {"smoothMs", p.smoothMs},
                          {"alignMs", p.alignMs},       {"shift", p.shift},
                          {"shiftRefused", p.shiftRefused}, {"closeMs", p.closeMs},
                          {"breaksClosed", p.breaksClosed}, {"breaksLeft", p.breaksLeft},
                          {"loopFit", p.loopFit},           {"fitMs", p.fitMs},
                          {"localUpdate", p.localUpdate},   {"localVertices", p.localVertices},
                          {"ms", stripesMs_}}
        .dump();
  }

  // The Hodge decomposition (Eq. 3, field/hodge_decomposition.h) of the current field, computed now (two Poisson
  // solves): {exact, coexact, harmonic (per edge, the oneForm's order), potential0 (per vertex), potential2 (per
  // face), metric (per edge: the diagonal inner product the parts are orthogonal in), metricName, milliseconds,
  // energyShares: {exact, coexact, harmonic}}, every array a copy of its own; or the error message (a string).
  val hodge() {
    val out = val::object();
    if (!ok([&] {
          const tvf::HodgeDecomposition h = need().hodgeDecomposition();
          const tvf::HodgeEnergyShares shares = tvf::hodgeEnergyShares(h);
          out.set("exact", copyOf(h.exact));
          out.set("coexact", copyOf(h.coexact));
          out.set("harmonic", copyOf(h.harmonic));
          out.set("potential0", copyOf(h.potential0));
          out.set("potential2", copyOf(h.potential2));
          out.set("metric", copyOf(h.metric));
          out.set("metricName", h.metricName);
          out.set("milliseconds", h.milliseconds);
          val s = val::object();
          s.set("exact", shares.exact);
          s.set("coexact", shares.coexact);
          s.set("harmonic", shares.harmonic);
          out.set("energyShares", s);
        }))
      return val(lastError_);
    return out;
  }

  // Face vectors (3 per face) and vertex vectors (3 per vertex) of the given 1-form (per edge, the oneForm's
  // order) by the designer's own reconstruction (Designer::reconstruct: the Whitney maps solve() and
  // vertexVectors() apply, one copy per mesh): {faceVectors, vertexVectors} as copies of their own, or the error
  // message.
  val reconstruct(const val& oneForm) {
    val out = val::object();
    if (!ok([&] {
          const tvf::Designer& d = need();
          const std::vector<double> c = emscripten::convertJSArrayToNumberVector<double>(oneForm);
          if (c.size() != static_cast<std::size_t>(d.topology().numEdges))
            throw tvf::InputError("reconstruct: expected " + std::to_string(d.topology().numEdges) +
                                  " values (one per edge), got " + std::to_string(c.size()));
          std::vector<double> faceVectors, vertexVectors;
          d.reconstruct(c.data(), faceVectors, vertexVectors);
          out.set("faceVectors", copyOf(faceVectors));
          out.set("vertexVectors", copyOf(vertexVectors));
        }))
      return val(lastError_);
    return out;
  }

  std::string singularitiesJson() const {
    return json([&] {
      nlohmann::json out = nlohmann::json::array();
      if (designer_)
        for (const tvf::Singularity& s : designer_->singularities())
          out.push_back({{"vertex", s.vertex}, {"index", s.index}, {"prescribed", s.prescribed}});
      return out;
    });
  }
  // The ids of the current constraints, in the order designJson() lists them: [id, ...].
  std::string constraintIdsJson() const {
    return json([&] {
      nlohmann::json out = nlohmann::json::array();
      if (designer_)
        for (const tvf::ConstraintSpec& c : designer_->constraints()) out.push_back(c.id);
      return out;
    });
  }
  // One constraint in the design format ("null" when there is no such id): what the page adds to its copy of
  // the design after an edit, instead of the whole document.
  std::string constraintJson(double id) const {
    return json([&] {
      if (designer_)
        for (const tvf::ConstraintSpec& c : designer_->constraints())
          if (c.id == id) return tvf::constraintToJson(c);
      return nlohmann::json();
    });
  }
  // Every constraint in constraintIdsJson()'s order, a prescribed singularity as {"type": "singularity",
  // "vertex", "index"}: the design document lists singularities apart ("singularities": [{vertex, index}]), so
  // its "constraints" alone do not line up with the ids.
  std::string constraintsJson() const {
    return json([&] {
      nlohmann::json out = nlohmann::json::array();
      if (designer_)
        for (const tvf::ConstraintSpec& c : designer_->constraints()) out.push_back(tvf::constraintToJson(c));
      return out;
    });
  }
  std::string statsJson() const {
    return json([&] { return tvf::statsJson(designer_ ? designer_->stats() : tvf::DesignStats{}); });
  }
  std::string designJson() const {
    return json([&] { return designer_ ? tvf::designDocument(*designer_) : nlohmann::json(); });
  }
  std::string fieldJson() const {
    return json([&] { return designer_ ? tvf::fieldDocument(*designer_) : nlohmann::json(); });
  }
  std::string applyDesignJson(const std::string& text) {
    return run([&] { tvf::applyDesignDocument(need(), nlohmann::json::parse(text)); });
  }

 private:
  tvf::Designer& need() const {
    if (!designer_) throw tvf::InputError("no mesh loaded");
    return *designer_;
  }

  void fitMemory(tvf::Designer& d) const { d.setFactorMemoryLimit(memoryLimit_ > 0 ? memoryLimit_ : availableHeapBytes()); }

  // {"ok": true, "settingsError": string|null, "restoreError": string|null} or {"ok": false, "error": string}.
  static std::string loadResult(bool ok, const std::string& error, const std::string& settingsError,
                                const std::string& restoreError) {
    const auto orNull = [](const std::string& s) { return s.empty() ? nlohmann::json() : nlohmann::json(s); };
    const nlohmann::json out = ok ? nlohmann::json{{"ok", true},
                                                   {"settingsError", orNull(settingsError)},
                                                   {"restoreError", orNull(restoreError)}}
                                  : nlohmann::json{{"ok", false}, {"error", error}};
    return out.dump();
  }

  // Whether the design given with a model took, and why not.
  struct Restored {
    bool ok = false;
    std::string error;
  };

  // Builds the next model aside; the current one is untouched until the caller assigns the result.
  std::unique_ptr<tvf::Designer> prepareModel(const val& bytes, const std::string& format,
                                              const std::string& settings, const std::string& design,
                                              std::string* settingsError, std::string* restoreError) const {
    Restored restored;
    auto next = openPrepared(bytes, format, settings, design, settingsError, &restored);
    solvePrepared(*next, restored);
    if (restoreError) *restoreError = restored.error;
    return next;
  }

  // The next model read, checked and configured (settings, design), not yet factored.
  std::unique_ptr<tvf::Designer> openPrepared(const val& bytes, const std::string& format,
                                              const std::string& settings, const std::string& design,
                                              std::string* settingsError, Restored* restored) const {
    return configured(parseMesh(bytes, format), settings, design, settingsError, restored);
  }

  // The file's mesh, as read (welded, not yet checked).
  static tvf::SurfaceMesh parseMesh(const val& bytes, const std::string& format) {
    if (bytes.isNull() || bytes.isUndefined()) throw tvf::InputError("no mesh data");
    // A Uint8Array (or any array-like); an ArrayBuffer is viewed as bytes.
    const bool buffer = bytes.instanceof(val::global("ArrayBuffer"));
    std::vector<uint8_t> data =
        emscripten::convertJSArrayToNumberVector<uint8_t>(buffer ? val::global("Uint8Array").new_(bytes) : bytes);
    if (data.empty()) throw tvf::InputError("the mesh file is empty");
    tvf::MeshFormat f;
    if (!parseFormat(format, data.data(), data.size(), f))
      throw tvf::InputError("unknown mesh format '" + format + "' (expected glb, gltf, obj, off, ply or '')");
    return tvf::loadMeshFromMemory(data.data(), data.size(), f);  // the bytes are freed on return
  }

  // A read mesh checked and configured (settings, design) as the next model, not yet factored.
  std::unique_ptr<tvf::Designer> configured(tvf::SurfaceMesh mesh, const std::string& settings,
                                            const std::string& design, std::string* settingsError,
                                            Restored* restored) const {
    auto next = std::make_unique<tvf::Designer>(std::move(mesh));
    next->setDeferredUpdates(deferUpdates_);
    if (!settings.empty()) {
      std::string error;
      if (!attempt(error, [&] {
            const nlohmann::json s = nlohmann::json::parse(settings);
            if (!s.is_object()) throw tvf::InputError("settings must be a JSON object");
            next->setBoundary(tvf::boundaryFromJson(s.value("boundary", nlohmann::json())));
            const nlohmann::json g = s.value("gamma", nlohmann::json(0.0));
            if (!g.is_number()) throw tvf::InputError("gamma must be a number");
            next->setGamma(g.get<double>());
            const nlohmann::json n = s.value("symmetry", nlohmann::json(1));
            if (!n.is_number_integer()) throw tvf::InputError("symmetry must be an integer");
            next->setSymmetry(n.get<int>());
            const nlohmann::json a = s.value("curvatureAlignment", nlohmann::json(0.0));
            if (!a.is_number()) throw tvf::InputError("curvatureAlignment must be a number");
            next->setCurvatureAlignment(a.get<double>());
            // A new design's feature angle: "auto" is the mesh's suggestion (35 degrees on a creased surface, 0
            // on a faceted curved one: mesh/feature_edges.h); a restored design's own features replace it below.
            const nlohmann::json f = s.value("featureAngle", nlohmann::json(0.0));
            if (f == "auto") next->setFeatures(next->suggestedFeatureAngle(), {}, {});
            else if (!f.is_number()) throw tvf::InputError("featureAngle must be a number or \"auto\"");
            else next->setFeatures(f.get<double>(), {}, {});
            const nlohmann::json x = s.value("exactSingularities", nlohmann::json(false));
            if (!x.is_boolean()) throw tvf::InputError("exactSingularities must be true or false");
            next->setExactSingularities(x.get<bool>());
          })) {
        if (settingsError) *settingsError = error;
        next->setBoundary(tvf::BoundaryCondition::makeFree());
        next->setGamma(0);
        next->setCurvatureAlignment(0);
        next->setSymmetry(1);
        next->setFeatures(0, {}, {});
        next->setExactSingularities(false);
      }
    }
    *restored = Restored{};
    if (!design.empty()) {
      std::string error;
      restored->ok = attempt(error, [&] { tvf::applyDesignDocument(*next, nlohmann::json::parse(design)); });
      if (!restored->ok) restored->error = error;
    }
    return next;
  }

  // Factors and solves a prepared model. A restored design the mesh cannot take (a field that is not finite, a
  // gamma whose factor does not fit) is dropped and reported; a mesh that cannot be factored even without it
  // fails.
  void solvePrepared(tvf::Designer& next, Restored& restored) const {
    fitMemory(next);
    std::string error;
    if (attempt(error, [&] { next.solve(); })) return;
    if (!restored.ok) throw tvf::InputError(error);
    restored.ok = false;
    restored.error = error;
    next.clearConstraints();
    next.setBoundary(tvf::BoundaryCondition::makeFree());
    next.setGamma(0);
    next.setFeatures(0, {}, {});
    next.setExactSingularities(false);
    next.solve();
  }
  template <typename F>
  std::string run(F&& f) {
    std::string error;
    attempt(error, std::forward<F>(f));
    lastError_ = error;
    return error;
  }
  template <typename F>
  bool ok(F&& f) {
    return attempt(lastError_, std::forward<F>(f));
  }
  template <typename F>
  int add(F&& f) {
    int32_t id = -1;
    if (!attempt(lastError_, [&] { id = f(); })) return -1;
    return id;
  }
  template <typename F>
  std::string json(F&& f) const {
    std::string out, error;
    if (!attempt(error, [&] { out = f().dump(); })) {
      lastError_ = error;
      return "null";
    }
    return out;
  }

  std::unique_ptr<tvf::Designer> designer_;
  std::unique_ptr<tvf::Designer> pending_;  // openParsed's model, until commitModel
  int modelSerial_ = 0;                      // one more per model made current
  tvf::DesignStripes stripes_;               // computeStripes's, of model stripesModel_
  int stripesModel_ = -1;
  double stripesMs_ = 0;
  bool stripesInterrupted_ = false;  // the last computeStripes was abandoned for a newer request
  tvf::KeptOrdering kept_;                   // keptOrderingJson()'s, viewed by keptOrderingPerm()
  std::vector<uint8_t> symbolicBytes_;       // its symbolic factor's, viewed by keptSymbolicBytes()
  std::unique_ptr<tvf::SurfaceMesh> parsed_;  // readModel's mesh, until openParsed
  Restored pendingRestored_;
  // reconstruct()'s Whitney maps for designer_'s mesh (built on first use; dropped when the model changes).
  double memoryLimit_ = 0;  // 0: what is left of the wasm address space
  bool deferUpdates_ = false;
  mutable std::string lastError_;
  std::vector<double> emptyD_;
  std::vector<int32_t> emptyI_;
  std::vector<float> emptyF_;
};

// ------------------------------------------------------------------------------------------ warm-up
// Runs the calls a design session makes (factor, solve with sources, edge/stroke updates and downdates,
// read-outs) `rounds` times on an icosphere, so that V8 compiles their hot functions with its optimizing tier
// before the user's first large factorization. Returns the milliseconds spent, or -1 on failure.
double warmUp(int levels, int rounds) {
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  const bool ok = attempt(error, [&] {
    tvf::Designer d(tvf::icosphere(std::max(0, std::min(levels, 6))));
    const tvf::SurfaceMesh& m = d.mesh();
    for (int r = 0; r < std::max(1, rounds); ++r) {
      d.clearConstraints();
      d.factor();
      d.addSource(m.triangles[0], 1.0);
      d.addSink(m.triangles[3 * (m.numFaces() / 2)], 1.0);
      d.solve();
      const int32_t e = d.addEdge(m.triangles[3], m.triangles[4], 0.1, 1.0);
      d.remove(e);
      std::vector<tvf::SurfacePoint> points;
      for (int32_t f = 0; f < std::min<int32_t>(m.numFaces(), 16); ++f) points.push_back({f, {0.2, 0.3, 0.5}});
      const int32_t s = d.addStroke(points, 1.0, 1.0);
      d.setWeight(s, 2.0);
      d.solve();
      d.remove(s);
      // The same stroke as the page's worker takes it: its update held beside the factor, put in after.
      d.setDeferredUpdates(true);
      const int32_t held = d.addStroke(points, 1.0, 1.0);
      d.solve();
      d.applyDeferredUpdates();
      d.remove(held);
      d.setDeferredUpdates(false);
    }
  });
  if (!ok) return -1;
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

EMSCRIPTEN_BINDINGS(tvf_core) {
  using emscripten::class_;
  using emscripten::function;
  class_<DesignerBinding>("Designer")
      .constructor<>()
      .function("loadMesh", &DesignerBinding::loadMesh)
      .function("loadModel", &DesignerBinding::loadModel)
      .function("commitModel", &DesignerBinding::commitModel)
      .function("readModel", &DesignerBinding::readModel)
      .function("parsedPositions", &DesignerBinding::parsedPositions)
      .function("parsedTriangles", &DesignerBinding::parsedTriangles)
      .function("openParsed", &DesignerBinding::openParsed)
      .function("pendingInfoJson", &DesignerBinding::pendingInfoJson)
      .function("pendingDesignJson", &DesignerBinding::pendingDesignJson)
      .function("pendingPositions", &DesignerBinding::pendingPositions)
      .function("pendingTriangles", &DesignerBinding::pendingTriangles)
      .function("pendingFaceAdjacency", &DesignerBinding::pendingFaceAdjacency)
      .function("pendingEdges", &DesignerBinding::pendingEdges)
      .function("pendingCornerUVs", &DesignerBinding::pendingCornerUVs)
      .function("pendingOrderingKey", &DesignerBinding::pendingOrderingKey)
      .function("pendingMeshHash", &DesignerBinding::pendingMeshHash)
      .function("adoptPendingOrdering", &DesignerBinding::adoptPendingOrdering)
      .function("keptOrderingJson", &DesignerBinding::keptOrderingJson)
      .function("keptOrderingPerm", &DesignerBinding::keptOrderingPerm)
      .function("keptSymbolicBytes", &DesignerBinding::keptSymbolicBytes)
      .function("releaseKeptOrdering", &DesignerBinding::releaseKeptOrdering)
      .function("keepPendingSymbolic", &DesignerBinding::keepPendingSymbolic)
      .function("preparePendingSystem", &DesignerBinding::preparePendingSystem)
      .function("setFactorMemoryLimit", &DesignerBinding::setFactorMemoryLimit)
      .function("gamma", &DesignerBinding::gamma)
      .function("infoJson", &DesignerBinding::infoJson)
      .function("setBoundaryJson", &DesignerBinding::setBoundaryJson)
      .function("setGamma", &DesignerBinding::setGamma)
      .function("setSymmetry", &DesignerBinding::setSymmetry)
      .function("symmetry", &DesignerBinding::symmetry)
      .function("setCurvatureAlignment", &DesignerBinding::setCurvatureAlignment)
      .function("curvatureAlignment", &DesignerBinding::curvatureAlignment)
      .function("setMetisOrdering", &DesignerBinding::setMetisOrdering)
      .function("setDeferredUpdates", &DesignerBinding::setDeferredUpdates)
      .function("applyDeferredUpdates", &DesignerBinding::applyDeferredUpdates)
      .function("setSolverThreads", &DesignerBinding::setSolverThreads)
      .function("solverThreads", &DesignerBinding::solverThreads)
      .function("factor", &DesignerBinding::factor)
      .function("solve", &DesignerBinding::solve)
      .function("addStroke", &DesignerBinding::addStroke)
      .function("addVector", &DesignerBinding::addVector)
      .function("addEdge", &DesignerBinding::addEdge)
      .function("addSource", &DesignerBinding::addSource)
      .function("addSink", &DesignerBinding::addSink)
      .function("addVortex", &DesignerBinding::addVortex)
      .function("addSingularity", &DesignerBinding::addSingularity)
      .function("moveSingularity", &DesignerBinding::moveSingularity)
      .function("setFeatures", &DesignerBinding::setFeatures)
      .function("featureAngle", &DesignerBinding::featureAngle)
      .function("setExactSingularities", &DesignerBinding::setExactSingularities)
      .function("exactSingularities", &DesignerBinding::exactSingularities)
      .function("featuresJson", &DesignerBinding::featuresJson)
      .function("featureEdges", &DesignerBinding::featureEdges)
      .function("constraintsJson", &DesignerBinding::constraintsJson)
      .function("remove", &DesignerBinding::remove)
      .function("setWeight", &DesignerBinding::setWeight)
      .function("setStrength", &DesignerBinding::setStrength)
      .function("clearConstraints", &DesignerBinding::clearConstraints)
      .function("lastError", &DesignerBinding::lastError)
      .function("hasMesh", &DesignerBinding::hasMesh)
      .function("positions", &DesignerBinding::positions)
      .function("triangles", &DesignerBinding::triangles)
      .function("edges", &DesignerBinding::edges)
      .function("oneForm", &DesignerBinding::oneForm)
      .function("faceVectors", &DesignerBinding::faceVectors)
      .function("vertexVectors", &DesignerBinding::vertexVectors)
      .function("cornerUVs", &DesignerBinding::cornerUVs)
      .function("sourceToWelded", &DesignerBinding::sourceToWelded)
      .function("singularitiesJson", &DesignerBinding::singularitiesJson)
      .function("statsJson", &DesignerBinding::statsJson)
      .function("constraintIdsJson", &DesignerBinding::constraintIdsJson)
      .function("constraintJson", &DesignerBinding::constraintJson)
      .function("designJson", &DesignerBinding::designJson)
      .function("applyDesignJson", &DesignerBinding::applyDesignJson)
      .function("addConstraintJson", &DesignerBinding::addConstraintJson)
      .function("fieldJson", &DesignerBinding::fieldJson)
      .function("hodge", &DesignerBinding::hodge)
      .function("computeStripes", &DesignerBinding::computeStripes)
      .function("stripeCornerPhase", &DesignerBinding::stripeCornerPhase)
      .function("stripeBranchIndex", &DesignerBinding::stripeBranchIndex)
      .function("stripeStatsJson", &DesignerBinding::stripeStatsJson)
      .function("stripesInterrupted", &DesignerBinding::stripesInterrupted)
      .function("reconstruct", &DesignerBinding::reconstruct);
  function("warmUp", &warmUp);
  // 1 in the plain build; in the build with pthreads (tvf_core_threads.mjs) one more than the helper threads
  // its pool started with.
  function("solverThreadsAvailable", emscripten::optional_override([] { return tvf::ThreadTeam::maxParts(); }));
}
