// SPDX-License-Identifier: GPL-2.0-or-later
// The quad remesher (core/quad/quad_remesh.h) for the page's quad worker (web/quad/): a free function over
// the mesh's and the field's arrays, so that it runs in a worker of its own while the design's worker stays
// free for edits, and a Cancel can end it at once.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/input_error.h"
#include "dec/hodge_star.h"
#include "mesh/mesh_checks.h"
#include "mesh/mesh_topology.h"
#include "quad/quad_remesh.h"
#include "quad/quad_remesh_json.h"

namespace {

using emscripten::val;

template <typename T>
val arrayCopy(const char* type, const std::vector<T>& v) {
  return val::global(type).new_(val(emscripten::typed_memory_view(v.size(), v.data())));
}

val errorResult(const std::string& message) {
  val out = val::object();
  out.set("error", message.empty() ? std::string("unknown error in the core") : message);
  return out;
}

tvf::SurfaceMesh meshFrom(const val& positions, const val& triangles, tvf::MeshTopology& topology) {
  tvf::SurfaceMesh mesh;
  mesh.positions = emscripten::convertJSArrayToNumberVector<double>(positions);
  mesh.triangles = emscripten::convertJSArrayToNumberVector<int32_t>(triangles);
  if (mesh.positions.size() % 3 != 0 || mesh.triangles.size() % 3 != 0 || mesh.triangles.empty())
    throw tvf::InputError("quad mesh: expected 3 numbers per vertex and 3 indices per triangle");
  tvf::MeshReport report = tvf::checkMesh(mesh);
  if (!report.usable()) throw tvf::InputError("quad mesh: " + report.firstFatal());
  topology = std::move(*report.topology);
  return mesh;
}

// positions (3 per vertex), triangles (3 per face), faceDirections (3 per face: the cross field's face
// vectors), options: {"edgeLength": L} or {"quads": N}, and "symmetry" (the field's); progress(stage,
// fraction) returning false cancels. Returns {error} or {positions, faceStart, faceVertices, irregular,
// statsJson}: copies, small beside the model.
val quadRemesh(const val& positions, const val& triangles, const val& faceDirections,
               const std::string& options, const val& progress) {
  try {
    tvf::MeshTopology topology;
    const tvf::SurfaceMesh mesh = meshFrom(positions, triangles, topology);
    const std::vector<double> directions = emscripten::convertJSArrayToNumberVector<double>(faceDirections);
    const nlohmann::json o =
        options.empty() ? nlohmann::json::object() : nlohmann::json::parse(options, nullptr, false);
    const int symmetry = o.is_object() && o.contains("symmetry") && o["symmetry"].is_number_integer()
                             ? o["symmetry"].get<int>()
                             : 4;
    const tvf::QuadRemeshOptions remeshOptions = tvf::quadRemeshOptionsFromJson(options);
    const tvf::MeshGeometry geometry = tvf::computeMeshGeometry(mesh, topology);
    const bool reports = progress.typeOf().as<std::string>() == "function";
    const tvf::QuadRemeshResult r =
        tvf::quadRemesh(mesh, topology, geometry, directions, symmetry, remeshOptions,
                        [&](const std::string& stage, double fraction) {
                          if (!reports) return true;
                          return !progress(stage, fraction).isFalse();
                        });
    val out = val::object();
    out.set("positions", arrayCopy("Float64Array", r.mesh.positions));
    out.set("faceStart", arrayCopy("Int32Array", r.mesh.faceStart));
    out.set("faceVertices", arrayCopy("Int32Array", r.mesh.faceVertices));
    out.set("irregular", arrayCopy("Int32Array", r.stats.irregular));
    out.set("statsJson", tvf::quadRemeshJson(r).dump());
    return out;
  } catch (const std::bad_alloc&) {
    return errorResult("out of memory: try a larger edge length");
  } catch (const std::exception& e) {
    return errorResult(e.what());
  } catch (...) {
    return errorResult("unknown error in the core");
  }
}

}  // namespace

EMSCRIPTEN_BINDINGS(tvf_quad) {
  emscripten::function("quadRemesh", &quadRemesh);
}
