#include "design/design_document.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>

#include "mesh/mesh_hash.h"

namespace tvf {
namespace {

using nlohmann::json;

const char* kindName(ConstraintKind k) {
  switch (k) {
    case ConstraintKind::Stroke:
      return "stroke";
    case ConstraintKind::Vector:
      return "vector";
    case ConstraintKind::Edge:
      return "edge";
    case ConstraintKind::Source:
      return "source";
    case ConstraintKind::Sink:
      return "sink";
    case ConstraintKind::Vortex:
      return "vortex";
    case ConstraintKind::Singularity:
      return "singularity";
  }
  return "";
}

double number(const json& object, const char* key, double fallback, const std::string& where) {
  if (!object.contains(key)) return fallback;
  const json& v = object.at(key);
  if (!v.is_number()) throw InputError(where + ": \"" + key + "\" must be a number");
  return v.get<double>();
}

// An element index as a JSON number: whole and within int32, checked on the double so that 1e12 is reported
// as 1e12 rather than wrapped.
int32_t elementIndex(double x, const std::string& what) {
  if (!std::isfinite(x) || x != std::floor(x) || x < -2147483648.0 || x > 2147483647.0) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", x);
    throw InputError(what + " must be an integer index (got " + text + ")");
  }
  return static_cast<int32_t>(x);
}

int32_t integer(const json& object, const char* key, const std::string& where) {
  if (!object.is_object() || !object.contains(key) || !object.at(key).is_number())
    throw InputError(where + ": \"" + key + "\" must be an integer");
  return elementIndex(object.at(key).get<double>(), where + ": \"" + key + "\"");
}

void numbers(const json& array, double* out, size_t n, const std::string& what) {
  if (!array.is_array() || array.size() != n)
    throw InputError(what + " must be a list of " + std::to_string(n) + " numbers");
  for (size_t k = 0; k < n; ++k) {
    if (!array[k].is_number())
      throw InputError(what + " must be a list of " + std::to_string(n) + " numbers");
    out[k] = array[k].get<double>();
  }
}

json vec3List(const std::vector<double>& flat) {
  json out = json::array();
  for (size_t k = 0; k + 2 < flat.size(); k += 3) out.push_back({flat[k], flat[k + 1], flat[k + 2]});
  return out;
}

json fingerprintJson(int32_t vertices, int32_t faces, uint64_t hash) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return {{"vertices", vertices}, {"faces", faces}, {"hash", hex}};
}

// The open mesh's fingerprint, from the hash the designer keeps.
json designerFingerprint(const Designer& designer) {
  return fingerprintJson(designer.mesh().numVertices(), designer.mesh().numFaces(), designer.meshHash());
}

std::string describeFingerprint(const json& f) {
  return std::to_string(f.value("vertices", 0)) + " vertices, " + std::to_string(f.value("faces", 0)) +
         " faces, hash " + f.value("hash", std::string("?"));
}

void checkSchema(const json& doc) {
  static const std::set<std::string> known{
      "schema",       "mesh",         "boundary",           "gamma",
      "constraints",  "symmetry",     "curvatureAlignment", "singularities",
      "featureAngle", "featureEdges", "exactSingularities"};
  if (doc.contains("schema")) {
    const json& s = doc["schema"];
    if (!s.is_string() || s.get<std::string>() != kDesignSchema)
      throw InputError("unknown design schema " + s.dump() + " (this version reads \"" + kDesignSchema +
                       "\")");
  }
  for (const auto& item : doc.items())
    if (!known.count(item.key()))
      throw InputError("not a design file: unknown key \"" + item.key() +
                       "\" (a design has schema, mesh, boundary, gamma, symmetry, curvatureAlignment, "
                       "constraints, singularities, exactSingularities, featureAngle and featureEdges)");
  if (!doc.contains("constraints")) throw InputError("not a design file: it has no \"constraints\" list");
}

void checkFingerprint(const Designer& designer, const json& doc) {
  if (!doc.contains("mesh")) return;  // older files carry none: indices are still range-checked
  const json& saved = doc["mesh"];
  if (!saved.is_object() || !saved.contains("hash") || !saved["hash"].is_string() ||
      !saved.value("vertices", json()).is_number_integer() ||
      !saved.value("faces", json()).is_number_integer())
    throw InputError("design: \"mesh\" must be {\"vertices\", \"faces\", \"hash\"}");
  const json current = designerFingerprint(designer);
  if (saved["vertices"] != current["vertices"] || saved["faces"] != current["faces"] ||
      saved["hash"] != current["hash"])
    throw InputError("this design was made for another mesh (" + describeFingerprint(saved) +
                     "); the open mesh has " + describeFingerprint(current));
}

// "singularities": [{"vertex": v, "index": k}, ...] as Singularity specs, in the file's order.
std::vector<ConstraintSpec> singularitiesFromJson(const json& doc) {
  std::vector<ConstraintSpec> specs;
  if (!doc.contains("singularities")) return specs;
  const json& list = doc["singularities"];
  if (!list.is_array())
    throw InputError("design: \"singularities\" must be a list of {\"vertex\", \"index\"}");
  for (size_t k = 0; k < list.size(); ++k) {
    const std::string where = "singularities[" + std::to_string(k) + "]";
    const json& entry = list[k];
    if (!entry.is_object() || !entry.contains("index") || entry.size() != 2)
      throw InputError(where + ": must be {\"vertex\": v, \"index\": k}");
    ConstraintSpec s;
    s.kind = ConstraintKind::Singularity;
    s.element = integer(entry, "vertex", where);
    s.value = number(entry, "index", 0.0, where);
    specs.push_back(s);
  }
  return specs;
}

// "exactSingularities": true when the field has exactly the prescribed singularities, none when none are
// prescribed (design/designer.h); absent: false, so designs made before it replay unchanged.
bool exactSingularitiesFromJson(const json& doc) {
  if (!doc.contains("exactSingularities")) return false;
  const json& x = doc["exactSingularities"];
  if (!x.is_boolean())
    throw InputError("design: \"exactSingularities\" must be true or false, got " + x.dump());
  return x.get<bool>();
}

// The design's sharp features: "featureAngle" (absent: 0, none detected, so designs made before features
// replay unchanged) and "featureEdges": {"add": [[a, b], ...], "remove": [...]}.
struct FeatureSettings {
  double angle = 0;
  std::vector<std::array<int32_t, 2>> add, remove;
};

std::vector<std::array<int32_t, 2>> vertexPairs(const json& list, const std::string& what) {
  if (!list.is_array()) throw InputError(what + " must be a list of vertex pairs [a, b]");
  std::vector<std::array<int32_t, 2>> pairs;
  for (size_t k = 0; k < list.size(); ++k) {
    const std::string where = what + " " + std::to_string(k);
    double ab[2];
    numbers(list[k], ab, 2, where);
    pairs.push_back({elementIndex(ab[0], where + " vertex"), elementIndex(ab[1], where + " vertex")});
  }
  return pairs;
}

FeatureSettings featuresFromJson(const json& doc) {
  FeatureSettings f;
  f.angle = number(doc, "featureAngle", 0.0, "design");
  if (!doc.contains("featureEdges")) return f;
  const json& edges = doc["featureEdges"];
  if (!edges.is_object())
    throw InputError("design: \"featureEdges\" must be {\"add\": [...], \"remove\": [...]}");
  for (const auto& item : edges.items())
    if (item.key() != "add" && item.key() != "remove")
      throw InputError("design: unknown key \"" + item.key() +
                       "\" in \"featureEdges\" (it has add and remove)");
  if (edges.contains("add")) f.add = vertexPairs(edges["add"], "featureEdges.add");
  if (edges.contains("remove")) f.remove = vertexPairs(edges["remove"], "featureEdges.remove");
  return f;
}

json pairList(const std::vector<std::array<int32_t, 2>>& pairs) {
  json out = json::array();
  for (const auto& p : pairs) out.push_back({p[0], p[1]});
  return out;
}

}  // namespace

json meshFingerprint(const SurfaceMesh& mesh) {
  return fingerprintJson(mesh.numVertices(), mesh.numFaces(), meshHash(mesh));
}

ConstraintSpec constraintFromJson(const json& c, size_t index) {
  const std::string where = "constraint " + std::to_string(index);
  if (!c.is_object() || !c.contains("type") || !c["type"].is_string())
    throw InputError(where + ": needs a \"type\"");
  const std::string type = c["type"];
  ConstraintSpec s;
  s.strength = number(c, "strength", 1.0, where);
  s.weight = number(c, "weight", 1.0, where);
  if (type == "stroke") {
    s.kind = ConstraintKind::Stroke;
    if (!c.contains("points") || !c["points"].is_array())
      throw InputError(where + ": a stroke needs \"points\"");
    for (const json& p : c["points"]) {
      SurfacePoint q{};
      q.face = integer(p, "face", where + " point");
      if (!p.is_object()) throw InputError(where + ": a stroke point must be {\"face\", \"bary\"}");
      numbers(p.value("bary", json()), q.bary, 3, where + " point \"bary\"");
      s.points.push_back(q);
    }
  } else if (type == "vector") {
    s.kind = ConstraintKind::Vector;
    s.element = integer(c, "face", where);
    numbers(c.value("vector", json()), s.vector, 3, where + " \"vector\"");
  } else if (type == "edge") {
    s.kind = ConstraintKind::Edge;
    double ij[2];
    numbers(c.value("edge", json()), ij, 2, where + " \"edge\"");
    s.edge[0] = elementIndex(ij[0], where + " \"edge\" vertex");
    s.edge[1] = elementIndex(ij[1], where + " \"edge\" vertex");
    if (!c.contains("value")) throw InputError(where + ": an edge constraint needs a \"value\"");
    s.value = number(c, "value", 0.0, where);
  } else if (type == "source" || type == "sink") {
    s.kind = type == "source" ? ConstraintKind::Source : ConstraintKind::Sink;
    s.element = integer(c, "vertex", where);
  } else if (type == "vortex") {
    s.kind = ConstraintKind::Vortex;
    s.element = integer(c, "face", where);
  } else if (type == "singularity") {
    // The page's constraint list and undo speak of a singularity as of any constraint; a design file lists
    // them under its own "singularities" key (applyDesignDocument refuses them among the constraints).
    s.kind = ConstraintKind::Singularity;
    s.element = integer(c, "vertex", where);
    if (!c.contains("index")) throw InputError(where + ": a singularity needs an \"index\"");
    s.value = number(c, "index", 0.0, where);
  } else {
    throw InputError(where + ": unknown type \"" + type + "\"");
  }
  return s;
}

json constraintToJson(const ConstraintSpec& s) {
  json c{{"type", kindName(s.kind)}};
  switch (s.kind) {
    case ConstraintKind::Stroke: {
      json points = json::array();
      for (const auto& p : s.points)
        points.push_back({{"face", p.face}, {"bary", {p.bary[0], p.bary[1], p.bary[2]}}});
      c["points"] = points;
      c["strength"] = s.strength;
      c["weight"] = s.weight;
      break;
    }
    case ConstraintKind::Vector:
      c["face"] = s.element;
      c["vector"] = {s.vector[0], s.vector[1], s.vector[2]};
      c["weight"] = s.weight;
      break;
    case ConstraintKind::Edge:
      c["edge"] = {s.edge[0], s.edge[1]};
      c["value"] = s.value;
      c["weight"] = s.weight;
      break;
    case ConstraintKind::Source:
    case ConstraintKind::Sink:
      c["vertex"] = s.element;
      c["strength"] = s.strength;
      break;
    case ConstraintKind::Vortex:
      c["face"] = s.element;
      c["strength"] = s.strength;
      break;
    case ConstraintKind::Singularity:
      c["vertex"] = s.element;
      c["index"] = s.value;
      break;
  }
  return c;
}

BoundaryCondition boundaryFromJson(const json& v) {
  if (v.is_null()) return BoundaryCondition::makeFree();
  if (v.is_string()) {
    const std::string name = v;
    if (name == "free") return BoundaryCondition::makeFree();
    if (name == "tangential") return BoundaryCondition::tangential();
    if (name == "normal") return BoundaryCondition::normal();
    throw InputError("boundary: unknown condition \"" + name +
                     "\" (free, tangential, normal or {\"angle\": radians})");
  }
  if (!v.is_object() || !v.contains("angle") || !v["angle"].is_number())
    throw InputError("boundary must be \"free\", \"tangential\", \"normal\" or {\"angle\": radians}");
  BoundaryCondition bc = BoundaryCondition::fixedAngle(v["angle"].get<double>());
  if (v.contains("perEdge")) {
    if (!v["perEdge"].is_array()) throw InputError("boundary.perEdge must be a list of [i, j, angle]");
    for (const json& e : v["perEdge"]) {
      double ija[3];
      numbers(e, ija, 3, "boundary.perEdge entry");
      bc.perEdge.push_back({elementIndex(ija[0], "boundary.perEdge vertex"),
                            elementIndex(ija[1], "boundary.perEdge vertex"), ija[2]});
    }
  }
  return bc;
}

json boundaryToJson(const BoundaryCondition& bc) {
  if (bc.free) return "free";
  if (bc.perEdge.empty() && bc.angle == M_PI / 2) return "tangential";
  if (bc.perEdge.empty() && bc.angle == 0) return "normal";
  json out{{"angle", bc.angle}};
  if (!bc.perEdge.empty()) {
    json list = json::array();
    for (const auto& e : bc.perEdge) list.push_back({e.i, e.j, e.angle});
    out["perEdge"] = list;
  }
  return out;
}

void applyDesignDocument(Designer& designer, const json& doc, bool fingerprint) {
  if (!doc.is_object()) throw InputError("a design must be a JSON object");
  checkSchema(doc);
  if (fingerprint) checkFingerprint(designer, doc);
  const BoundaryCondition bc = boundaryFromJson(doc.value("boundary", json()));
  const double gamma = number(doc, "gamma", 0.0, "design");
  const double symmetryValue = number(doc, "symmetry", 1.0, "design");
  if (symmetryValue != std::floor(symmetryValue) || symmetryValue < 1 || symmetryValue > 6)
    throw InputError("design: \"symmetry\" must be an integer from 1 to 6 (1 vector, 2 line, 4 cross field)");
  const int symmetry = static_cast<int>(symmetryValue);
  const double alignment = number(doc, "curvatureAlignment", 0.0, "design");
  std::vector<ConstraintSpec> specs;
  if (doc.contains("constraints")) {
    if (!doc["constraints"].is_array()) throw InputError("design: \"constraints\" must be a list");
    for (size_t k = 0; k < doc["constraints"].size(); ++k) {
      specs.push_back(constraintFromJson(doc["constraints"][k], k));
      if (specs.back().kind == ConstraintKind::Singularity)
        throw InputError(
            "constraint " + std::to_string(k) +
            ": a singularity belongs in the design's \"singularities\" list, not in \"constraints\"");
    }
  }
  const size_t numConstraints = specs.size();
  for (const ConstraintSpec& s : singularitiesFromJson(doc)) specs.push_back(s);
  const FeatureSettings features = featuresFromJson(doc);
  const bool exact = exactSingularitiesFromJson(doc);
  // Apply to a scratch copy of the settings first so a bad entry leaves the designer untouched.
  const BoundaryCondition oldBc = designer.boundary();
  const double oldGamma = designer.gamma();
  const int oldSymmetry = designer.symmetry();
  const double oldAlignment = designer.curvatureAlignment();
  const bool oldExact = designer.exactSingularities();
  const std::vector<ConstraintSpec> oldSpecs = designer.constraints();  // singularities among them
  const FeatureSettings oldFeatures{designer.featureAngle(), designer.featureEdgesAdded(),
                                    designer.featureEdgesRemoved()};
  // Constraints first, then the prescribed singularities (the order of their ids in the saved file).
  const auto where = [&](size_t k) {
    if (k < numConstraints) return "constraint " + std::to_string(k);
    return "singularities[" + std::to_string(k - numConstraints) + "]";
  };
  const auto replace = [&](const BoundaryCondition& b, double g, int n, double s, const FeatureSettings& f,
                           bool x, const std::vector<ConstraintSpec>& list, bool annotate) {
    designer.setBoundary(b);
    designer.setGamma(g);
    designer.clearConstraints();
    designer.setCurvatureAlignment(0);  // before the symmetry, which refuses an alignment it cannot take
    designer.setSymmetry(n);
    designer.setCurvatureAlignment(s);
    designer.setFeatures(f.angle, f.add, f.remove);
    designer.setExactSingularities(x);  // before the singularities: it chooses the system they go into
    for (size_t k = 0; k < list.size(); ++k) {
      try {
        designer.add(list[k]);
      } catch (const InputError& e) {
        if (!annotate) throw;
        throw InputError(where(k) + ": " + e.what());
      }
    }
  };
  try {
    replace(bc, gamma, symmetry, alignment, features, exact, specs, true);
  } catch (const InputError&) {
    replace(oldBc, oldGamma, oldSymmetry, oldAlignment, oldFeatures, oldExact, oldSpecs, false);
    throw;
  }
}

json designDocument(const Designer& designer) {
  json constraints = json::array();
  std::vector<ConstraintSpec> singularities;
  for (const auto& s : designer.constraints()) {
    if (s.kind == ConstraintKind::Singularity)
      singularities.push_back(s);
    else
      constraints.push_back(constraintToJson(s));
  }
  std::stable_sort(singularities.begin(), singularities.end(),
                   [](const ConstraintSpec& a, const ConstraintSpec& b) { return a.id < b.id; });
  json doc = {{"schema", kDesignSchema},
              {"mesh", designerFingerprint(designer)},
              {"boundary", boundaryToJson(designer.boundary())},
              {"gamma", designer.gamma()},
              {"constraints", constraints}};
  // Written only when not the default, so a vector-field design reads (and hashes) as it always did.
  if (designer.symmetry() != 1) doc["symmetry"] = designer.symmetry();
  if (designer.curvatureAlignment() != 0) doc["curvatureAlignment"] = designer.curvatureAlignment();
  if (!singularities.empty()) {
    json list = json::array();
    for (const auto& s : singularities) list.push_back({{"vertex", s.element}, {"index", s.value}});
    doc["singularities"] = list;
  }
  if (designer.exactSingularities()) doc["exactSingularities"] = true;
  if (designer.featureAngle() != 0) doc["featureAngle"] = designer.featureAngle();
  if (!designer.featureEdgesAdded().empty() || !designer.featureEdgesRemoved().empty())
    doc["featureEdges"] = {{"add", pairList(designer.featureEdgesAdded())},
                           {"remove", pairList(designer.featureEdgesRemoved())}};
  return doc;
}

json statsJson(const DesignStats& s) {
  return {{"analyzeMs", s.analyzeMs},
          {"factorMs", s.factorMs},
          {"convertMs", s.convertMs},
          {"dissectionMs", s.dissectionMs},
          {"updateMs", s.updateMs},
          {"deferredUpdateMs", s.deferredUpdateMs},
          {"solveMs", s.solveMs},
          {"reconstructMs", s.reconstructMs},
          {"rowsMs", s.rowsMs},
          {"rhsMs", s.rhsMs},
          {"analysisReused", s.analysisReused},
          {"symbolicReused", s.symbolicReused},
          {"precisionRefactors", s.precisionRefactors},
          {"incrementalSolves", s.incrementalSolves},
          {"supernodalSolves", s.supernodalSolves},
          {"nnzPerRowM", s.nnzPerRowM},
          {"nnzPerRowL", s.nnzPerRowL},
          {"positiveAreaFallbackVertices", s.positiveAreaFallbackVertices},
          {"kernelHandling", s.kernelHandling},
          {"kernelShift", s.kernelShift},
          {"factorKind", s.factorKind},
          {"factorThreads", s.factorThreads},
          {"factorGroups", s.factorGroups},
          {"singleThreadWhy", s.singleThreadWhy},
          {"symmetry", s.symmetry},
          {"factorizations", s.factorizations},
          {"inverseIterations", s.inverseIterations},
          {"smoothestEigenvalue", s.smoothestEigenvalue},
          {"singularityMode", s.singularityMode},
          {"eulerCharacteristic", s.eulerCharacteristic},
          {"prescribedIndex", s.prescribedIndex},
          {"freeIndex", s.freeIndex},
          {"featureEdges", s.featureEdges},
          {"warnings", s.warnings}};
}

json fieldDocument(const Designer& designer) {
  json edges = json::array();
  const auto& ev = designer.edgeVertices();
  for (size_t k = 0; k + 1 < ev.size(); k += 2) edges.push_back({ev[k], ev[k + 1]});
  json singularities = json::array();
  for (const auto& s : designer.singularities())
    singularities.push_back({{"vertex", s.vertex}, {"index", s.index}, {"prescribed", s.prescribed}});
  json features = json::array();
  for (const int32_t e : designer.featureEdges()) features.push_back({ev[2 * e], ev[2 * e + 1]});
  // With prescribed singularities even N = 1 is a unit direction field (design/designer.h): no 1-form.
  if (designer.symmetry() != 1 || designer.oneForm().empty())
    return {{"symmetry", designer.symmetry()},
            {"faceDirections", vec3List(designer.faceVectors())},
            {"vertexDirections", vec3List(designer.vertexVectors())},
            {"singularities", singularities},
            {"featureEdges", features},
            {"stats", statsJson(designer.stats())}};
  return {{"edges", edges},
          {"oneForm", designer.oneForm()},
          {"faceVectors", vec3List(designer.faceVectors())},
          {"vertexVectors", vec3List(designer.vertexVectors())},
          {"singularities", singularities},
          {"featureEdges", features},
          {"stats", statsJson(designer.stats())}};
}

}  // namespace tvf
