// SPDX-License-Identifier: GPL-2.0-or-later
//
// embind bindings of the exemplar analysis for texture synthesis (core/texture/), used by web/synthesis/.
// Same conventions as bindings.cpp: nothing throws into JS (calls that can fail return '' or the error
// message), and array read-outs are typed_memory_view()s into wasm memory, valid until the next analyze call
// on the same object or memory growth — copy them before doing anything else with the module.
//
//   const a = new Module.ExemplarAnalysis();
//   a.analyzeProcedural('stripes', 64, 1)      // or a.analyzeRGBA8(uint8Array, size): '' or an error message
//   a.size(), a.numLevels(), a.statsJson()
//   a.rgba8()                                  // the exemplar, 4 bytes per pixel
//   a.colour(s), a.appearance(s), a.neighbourhood(s), a.candidates(s), a.projection(s), a.projectionOffset(s)
//   a.delete()
// Module.proceduralExemplarNames() returns a JSON array of names.
//
//   const t = new Module.TextureAtlasBuilder();
//   t.generate(positions, triangles, resolution, gutter)   // '' or an error message
//   (core/texture/texture_atlas) t.cornerUVs()    // Float32Array view, 6 per face; t.faceCharts():
//   Int32Array view; t.statsJson() t.check(cornerUVs, numFaces, resolution)               // JSON {usable,
//   reason, coverage, overlap, ...} t.delete()
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <exception>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mesh/surface_mesh.h"
#include "texture/exemplar_analysis.h"
#include "texture/procedural_exemplars.h"
#include "texture/texture_atlas.h"

namespace {

using emscripten::val;

class ExemplarAnalysisBinding {
 public:
  std::string analyzeProcedural(const std::string& name, int size, double seed) {
    return run([&] { return tvf::makeProceduralExemplar(name, size, static_cast<unsigned>(seed)); });
  }
  // bytes: RGBA8, size x size (alpha ignored).
  std::string analyzeRGBA8(const val& bytes, int size) {
    return run([&] {
      const std::vector<uint8_t> data = emscripten::convertJSArrayToNumberVector<uint8_t>(bytes);
      if (data.size() != 4u * static_cast<size_t>(size) * static_cast<size_t>(size))
        throw tvf::InputError("exemplar: expected " + std::to_string(4 * size * size) + " bytes (RGBA, " +
                              std::to_string(size) + "x" + std::to_string(size) + "), got " +
                              std::to_string(data.size()));
      return tvf::exemplarFromRGBA8(data.data(), size, size);
    });
  }

  int size() const { return analysis_.size(); }
  int numLevels() const { return static_cast<int>(tables_.size()); }
  val rgba8() const { return view(rgba_); }
  val colour(int s) const { return level(s, &tvf::GpuLevelTables::colour); }
  val appearance(int s) const { return level(s, &tvf::GpuLevelTables::appearance); }
  val neighbourhood(int s) const { return level(s, &tvf::GpuLevelTables::neighbourhood); }
  val candidates(int s) const { return level(s, &tvf::GpuLevelTables::candidates); }
  val projection(int s) const { return level(s, &tvf::GpuLevelTables::projection); }
  val projectionOffset(int s) const { return level(s, &tvf::GpuLevelTables::projectionOffset); }

  // {size, levels, timings: {stackMs, appearanceMs, neighbourhoodMs, kCoherenceMs, totalMs},
  //  perLevel: [{spacing, appearanceVarianceKept, neighbourhoodVarianceKept, k, radius, lattice}]}
  std::string statsJson() const {
    nlohmann::json out;
    out["size"] = analysis_.size();
    out["levels"] = analysis_.numLevels();
    const tvf::AnalysisTimings& t = analysis_.timings;
    out["timings"] = {{"stackMs", t.stackMs},
                      {"appearanceMs", t.appearanceMs},
                      {"neighbourhoodMs", t.neighbourhoodMs},
                      {"kCoherenceMs", t.kCoherenceMs},
                      {"totalMs", t.totalMs}};
    out["perLevel"] = nlohmann::json::array();
    for (const tvf::AnalysisLevel& l : analysis_.levels)
      out["perLevel"].push_back({{"spacing", l.appearance.spacing},
                                 {"appearanceVarianceKept", l.appearance.basis.varianceKept},
                                 {"neighbourhoodVarianceKept", l.neighbourhood.basis.varianceKept},
                                 {"k", l.candidates.k},
                                 {"radius", l.candidates.radius},
                                 {"lattice", l.candidates.step}});
    return out.dump();
  }

 private:
  template <typename F>
  std::string run(F&& makeImage) {
    try {
      const tvf::ExemplarImage image = makeImage();
      tvf::ExemplarAnalysis analysis = tvf::analyzeExemplar(image);
      std::vector<tvf::GpuLevelTables> tables;
      for (int s = 0; s < analysis.numLevels(); ++s) tables.push_back(tvf::gpuTables(analysis, s));
      analysis_ = std::move(analysis);
      tables_ = std::move(tables);
      rgba_ = tvf::exemplarToRGBA8(image);
      return "";
    } catch (const std::bad_alloc&) {
      return "out of memory";
    } catch (const std::exception& e) {
      return e.what()[0] ? e.what() : "unknown error in the core";
    } catch (...) {
      return "unknown error in the core";
    }
  }
  template <typename T>
  static val view(const std::vector<T>& v) {
    return val(emscripten::typed_memory_view(v.size(), v.data()));
  }
  val level(int s, std::vector<float> tvf::GpuLevelTables::*member) const {
    if (s < 0 || s >= static_cast<int>(tables_.size())) return view(empty_);
    return view(tables_[s].*member);
  }

  tvf::ExemplarAnalysis analysis_;
  std::vector<tvf::GpuLevelTables> tables_;
  std::vector<uint8_t> rgba_;
  std::vector<float> empty_;
};

class TextureAtlasBinding {
 public:
  // positions: 3 numbers per vertex; triangles: 3 indices per face (any array-like of numbers).
  std::string generate(const val& positions, const val& triangles, int resolution, int gutter) {
    try {
      tvf::SurfaceMesh mesh;
      mesh.positions = emscripten::convertJSArrayToNumberVector<double>(positions);
      mesh.triangles = emscripten::convertJSArrayToNumberVector<int32_t>(triangles);
      atlas_ = tvf::generateAtlas(mesh, resolution, gutter);
      return "";
    } catch (const std::bad_alloc&) {
      return "out of memory";
    } catch (const std::exception& e) {
      return e.what()[0] ? e.what() : "unknown error in the core";
    }
  }
  val cornerUVs() const {
    return val(emscripten::typed_memory_view(atlas_.cornerUVs.size(), atlas_.cornerUVs.data()));
  }
  val faceCharts() const {
    return val(emscripten::typed_memory_view(atlas_.faceChart.size(), atlas_.faceChart.data()));
  }
  // {resolution, gutter, charts, splits, keptPieces, packAttempts, ms, chartMs, coverage, overlap,
  //  flippedFaces, degenerateFaces, densityP05, densityP95, densityMin, densityMax, texelsPerUnitLength,
  //  stretchL2, seamShare, used}
  std::string statsJson() const {
    const tvf::AtlasMeasures& m = atlas_.measures;
    return nlohmann::json{{"resolution", atlas_.resolution},
                          {"gutter", atlas_.gutter},
                          {"charts", atlas_.numCharts},
                          {"splits", atlas_.splits},
                          {"keptPieces", atlas_.keptPieces},
                          {"packAttempts", atlas_.packAttempts},
                          {"ms", atlas_.milliseconds},
                          {"chartMs", atlas_.chartMilliseconds},
                          {"coverage", m.coverage},
                          {"overlap", m.overlap},
                          {"flippedFaces", m.flippedFaces},
                          {"degenerateFaces", m.degenerateFaces},
                          {"densityP05", m.densityP05},
                          {"densityP95", m.densityP95},
                          {"densityMin", m.densityMin},
                          {"densityMax", m.densityMax},
                          {"texelsPerUnitLength", m.texelsPerUnitLength},
                          {"stretchL2", m.stretchL2},
                          {"seamShare", m.seamShare},
                          {"used", atlas_.used}}
        .dump();
  }
  std::string check(const val& cornerUVs, int numFaces, int resolution) const {
    try {
      const std::vector<float> uv = emscripten::convertJSArrayToNumberVector<float>(cornerUVs);
      const tvf::AtlasCheck c = tvf::checkAtlasUVs(uv, numFaces, resolution);
      return nlohmann::json{{"usable", c.usable},      {"reason", c.reason},   {"coverage", c.coverage},
                            {"overlap", c.overlap},    {"outside", c.outside}, {"degenerate", c.degenerate},
                            {"nonFinite", c.nonFinite}}
          .dump();
    } catch (const std::exception& e) {
      return nlohmann::json{{"usable", false}, {"reason", e.what()}}.dump();
    }
  }

 private:
  tvf::TextureAtlas atlas_;
};

std::string proceduralExemplarNamesJson() {
  return nlohmann::json(tvf::proceduralExemplarNames()).dump();
}

}  // namespace

EMSCRIPTEN_BINDINGS(tvf_texture) {
  emscripten::class_<ExemplarAnalysisBinding>("ExemplarAnalysis")
      .constructor<>()
      .function("analyzeProcedural", &ExemplarAnalysisBinding::analyzeProcedural)
      .function("analyzeRGBA8", &ExemplarAnalysisBinding::analyzeRGBA8)
      .function("size", &ExemplarAnalysisBinding::size)
      .function("numLevels", &ExemplarAnalysisBinding::numLevels)
      .function("rgba8", &ExemplarAnalysisBinding::rgba8)
      .function("colour", &ExemplarAnalysisBinding::colour)
      .function("appearance", &ExemplarAnalysisBinding::appearance)
      .function("neighbourhood", &ExemplarAnalysisBinding::neighbourhood)
      .function("candidates", &ExemplarAnalysisBinding::candidates)
      .function("projection", &ExemplarAnalysisBinding::projection)
      .function("projectionOffset", &ExemplarAnalysisBinding::projectionOffset)
      .function("statsJson", &ExemplarAnalysisBinding::statsJson);
  emscripten::function("proceduralExemplarNames", &proceduralExemplarNamesJson);
  emscripten::class_<TextureAtlasBinding>("TextureAtlasBuilder")
      .constructor<>()
      .function("generate", &TextureAtlasBinding::generate)
      .function("cornerUVs", &TextureAtlasBinding::cornerUVs)
      .function("faceCharts", &TextureAtlasBinding::faceCharts)
      .function("statsJson", &TextureAtlasBinding::statsJson)
      .function("check", &TextureAtlasBinding::check);
}
