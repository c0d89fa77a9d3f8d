// SPDX-License-Identifier: GPL-2.0-or-later
//
// embind bindings of stripe patterns (core/direction/stripe_pattern.h). Same conventions as bindings.cpp:
// nothing throws into JS (compute returns '' or the error message), and the read-outs are
// typed_memory_view()s into wasm memory, valid until the next compute on the same object or memory growth:
// copy them first.
//
//   const s = new Module.StripePatternBuilder();
//   s.compute(positions, triangles, vertexDirections, optionsJson)   // '' or an error message
//   //   positions: 3 per vertex; triangles: 3 per face; vertexDirections: 3 per vertex (the field's
//   //   representatives); optionsJson: {symmetry: 1|2|4, frequency (stripes per unit length),
//   //   vertexFrequencyScale?: [one per vertex], tolerance?, maxIterations?}
//   s.cornerPhase()     // Float32Array view: families x 3 per face (family-major), radians
//   s.branchIndex()     // Int8Array view: families per face
//   s.fieldSingular()   // Uint8Array view: 1 per face
//   s.statsJson()       // {families, eigenvalue, residual, iterations, factorMs, iterateMs, warmStart,
//                       //  analysisReused}
//   s.delete()
// A compute on the same mesh as the one before reuses its factor's analysis and, for the same symmetry,
// starts from its pattern (core/direction/stripe_pattern.h's StripeWorkspace).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <exception>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/input_error.h"
#include "direction/stripe_pattern.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace {

using emscripten::val;

class StripePatternBinding {
 public:
  std::string compute(const val& positions, const val& triangles, const val& directions,
                      const std::string& json) {
    try {
      tvf::SurfaceMesh mesh;
      mesh.positions = emscripten::convertJSArrayToNumberVector<double>(positions);
      mesh.triangles = emscripten::convertJSArrayToNumberVector<int32_t>(triangles);
      const std::vector<double> dirs = emscripten::convertJSArrayToNumberVector<double>(directions);
      if (mesh.positions.size() % 3 || mesh.triangles.size() % 3 || mesh.triangles.empty())
        throw tvf::InputError("stripe pattern: positions and triangles must come in threes");
      for (int32_t v : mesh.triangles)
        if (v < 0 || v >= mesh.numVertices())
          throw tvf::InputError("stripe pattern: a vertex index out of range");
      const nlohmann::json o = json.empty() ? nlohmann::json::object() : nlohmann::json::parse(json);
      tvf::StripeOptions options;
      options.symmetry = o.value("symmetry", 1);
      options.frequency = o.value("frequency", 1.0);
      options.tolerance = o.value("tolerance", options.tolerance);
      options.maxIterations = o.value("maxIterations", options.maxIterations);
      if (o.contains("vertexFrequencyScale"))
        options.vertexFrequencyScale = o.at("vertexFrequencyScale").get<std::vector<double>>();
      // Another mesh: its topology and geometry derived once, and nothing of the workspace holds (its
      // factor's analysis, its psi).
      if (mesh.triangles != triangles_ || mesh.positions != positions_) {
        topology_ = tvf::buildTopology(mesh);
        geometry_ = tvf::computeMeshGeometry(mesh, topology_);
        workspace_.clear();
        triangles_ = mesh.triangles;
        positions_ = mesh.positions;
      }
      warmStart_ = workspace_.symmetry == options.symmetry && !workspace_.psi.empty();
      pattern_ = tvf::stripePattern(mesh, topology_, geometry_, dirs, options, &workspace_);
      return "";
    } catch (const std::bad_alloc&) {
      return "out of memory";
    } catch (const std::exception& e) {
      return e.what()[0] ? e.what() : "unknown error in the core";
    }
  }
  val cornerPhase() const { return view(pattern_.cornerPhase); }
  val branchIndex() const { return view(pattern_.branchIndex); }
  val fieldSingular() const { return view(pattern_.fieldSingular); }
  std::string statsJson() const {
    return nlohmann::json{{"families", pattern_.families}, {"eigenvalue", pattern_.eigenvalue},
                          {"residual", pattern_.residual}, {"iterations", pattern_.iterations},
                          {"factorMs", pattern_.factorMs}, {"iterateMs", pattern_.iterateMs},
                          {"warmStart", warmStart_},       {"analysisReused", pattern_.analysisReused}}
        .dump();
  }

 private:
  template <typename T>
  static val view(const std::vector<T>& v) {
    return val(emscripten::typed_memory_view(v.size(), v.data()));
  }

  tvf::StripePattern pattern_;
  std::vector<int32_t> triangles_;
  std::vector<double> positions_;
  tvf::MeshTopology topology_;
  tvf::MeshGeometry geometry_;
  tvf::StripeWorkspace workspace_;
  bool warmStart_ = false;
};

}  // namespace

EMSCRIPTEN_BINDINGS(tvf_stripes) {
  emscripten::class_<StripePatternBinding>("StripePatternBuilder")
      .constructor<>()
      .function("compute", &StripePatternBinding::compute)
      .function("cornerPhase", &StripePatternBinding::cornerPhase)
      .function("branchIndex", &StripePatternBinding::branchIndex)
      .function("fieldSingular", &StripePatternBinding::fieldSingular)
      .function("statsJson", &StripePatternBinding::statsJson);
}
