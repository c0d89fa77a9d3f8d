// SPDX-License-Identifier: GPL-2.0-or-later
//
// embind bindings of the exporters (core/design/field_export.h): the page's export buttons produce the
// same bytes as `tvf export` for the same mesh file and one-form. The exporter takes the welded mesh the
// page's Designer already holds (no second parse of the model file); of a glTF/GLB file it keeps only the
// document, so a GLB export keeps the model's own glTF. Same conventions as bindings.cpp: nothing throws into
// JS (failures return null or '' and leave the message in lastError()).
//
//   const x = new Module.FieldExporter();
//   x.setMesh(positions, triangles, cornerUVs, sourceToWelded)   // the Designer's welded mesh (copied in;
//                                             // pass copies, not views of wasm memory); '' or an error message
//   x.setSource(uint8Array, 'glb')            // glTF/GLB: the document kept for re-export; other formats keep
//                                             // nothing; '' or an error message
//   x.atlasNote()                             // '' when the model's own UVs are the atlas, else why not
//                                             // (then exports generate one: texture/texture_atlas.h)
//   x.flowMapPng(oneForm, optionsJson)        // Uint8Array (a copy) or null
//   x.glb(oneForm, designJson, optionsJson, texture)   // Uint8Array or null; designJson may be ''
//   x.directionFlowMapPng(faceDirections, symmetry, optionsJson)            // a line or cross field (N >= 2):
//   x.directionGlb(faceDirections, symmetry, designJson, optionsJson, texture)  // one unit representative per
//   x.rawField(faceDirections, symmetry)      // face, combed per chart by the core; rawField: Directional's text
//   x.singFile(symmetry, singularitiesJson)   // Directional's .sing of [{vertex, index}, ...] (io/sing_file.h)
//   x.rosyFile(faceDirections, symmetry)      // QuadWild's .rosy of a cross field (io/rosy_file.h)
//   x.sharpFile(featureEdges)                 // QuadWild's .sharp of the edges in use (io/sharp_file.h)
//                                             // each: the file's text, or '' with lastError() set
//   x.lastError(), x.delete()
//   Module.embeddedDesignJson(uint8Array)     // the design a GLB carries, 'null' when none
//   Module.readSingJson(text)                 // a .sing read: {symmetry, singularities: [{vertex, index}]}
//                                             // or {error}: the reader's refusal naming the line
// optionsJson: {size, convention: 'gltf'|'opengl', bits: 8|16, gutter, strength, rotation, embedFlowMap,
// embedDesign}; every key optional (defaults as the CLI's).
// texture: null, or {png: Uint8Array, cornerUVs: Float32Array (6 per face)}: a base-colour image over its own
// UVs (e.g. the synthesized texture in its atlas; image row 0 = v 0, as glTF samples it). Those UVs then index
// the flow map too; unless they are the model's own, the GLB is a new document over the welded mesh with a
// vertex per (welded vertex, UV) pair (io/gltf_writer.h). Or {stripes: {cornerPhase, branchIndex, families,
// profile, width?, light?, dark?}}: the page's stripe pattern (Designer.computeStripes), drawn into the export's
// atlas (direction/stripe_texture.h) as `tvf export --stripes` draws it, its phase as a texture coordinate
// (TEXCOORD_1, or a kept primitive's first free set: io/gltf_writer.h).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "design/field_export.h"
#include "direction/stripe_texture.h"
#include "io/png_writer.h"
#include "io/gltf_writer.h"
#include "io/mesh_io.h"
#include "io/rosy_file.h"
#include "io/sharp_file.h"
#include "io/sing_file.h"

namespace {

using emscripten::val;

bool isNullish(const val& v) {
  return v.isNull() || v.isUndefined();
}

std::vector<uint8_t> bytesOf(const val& array) {
  const bool buffer = array.instanceof (val::global("ArrayBuffer"));
  return emscripten::convertJSArrayToNumberVector<uint8_t>(buffer ? val::global("Uint8Array").new_(array)
                                                                  : array);
}

val toUint8Array(const std::vector<uint8_t>& bytes) {
  // A copy: a view into wasm memory would go stale on the next allocation.
  return val::global("Uint8Array").new_(val(emscripten::typed_memory_view(bytes.size(), bytes.data())));
}

template <typename T>
std::vector<T> numbersOf(const val& array) {
  return isNullish(array) ? std::vector<T>{} : emscripten::convertJSArrayToNumberVector<T>(array);
}

tvf::FieldExportOptions optionsFrom(const std::string& text) {
  tvf::FieldExportOptions o;
  if (text.empty()) return o;
  const nlohmann::json j = nlohmann::json::parse(text);
  o.size = j.value("size", o.size);
  o.convention = tvf::flowMapConventionFromName(j.value("convention", std::string("gltf")));
  o.bits = j.value("bits", o.bits);
  o.gutterTexels = j.value("gutter", o.gutterTexels);
  o.anisotropyStrength = j.value("strength", o.anisotropyStrength);
  o.anisotropyRotation = j.value("rotation", o.anisotropyRotation);
  o.embedFlowMap = j.value("embedFlowMap", o.embedFlowMap);
  o.embedDesign = j.value("embedDesign", o.embedDesign);
  return o;
}

class FieldExporterBinding {
 public:
  std::string setMesh(const val& positions, const val& triangles, const val& cornerUVs,
                      const val& sourceToWelded) {
    return run([&] {
      auto mesh = std::make_unique<Mesh>();
      tvf::SurfaceMesh& s = mesh->surface;
      s.positions = numbersOf<double>(positions);
      s.triangles = numbersOf<int32_t>(triangles);
      s.cornerUVs = numbersOf<float>(cornerUVs);
      s.sourceToWelded = numbersOf<int32_t>(sourceToWelded);
      if (s.positions.size() % 3 || s.triangles.empty() || s.triangles.size() % 3)
        throw tvf::InputError("export: positions and triangles must hold 3 values per vertex and face");
      if (!s.cornerUVs.empty() && s.cornerUVs.size() != 2 * s.triangles.size())
        throw tvf::InputError("export: expected 6 UV values per face");
      for (const int32_t v : s.triangles)
        if (v < 0 || v >= s.numVertices()) throw tvf::InputError("export: a triangle names no vertex");
      mesh->topology = tvf::buildTopology(s);
      mesh_ = std::move(mesh);
    });
  }

  // The document of the model file (glTF/GLB); nothing for the other formats, whose GLB is built anew.
  std::string setSource(const val& bytes, const std::string& format) {
    return run([&] {
      source_.reset();
      const std::vector<uint8_t> data = bytesOf(bytes);
      if (data.empty()) throw tvf::InputError("the mesh file is empty");
      tvf::MeshFormat f = tvf::formatFromBytes(data.data(), data.size());
      if (!format.empty()) f = tvf::formatFromPath("model." + format);
      if (f == tvf::MeshFormat::Glb || f == tvf::MeshFormat::Gltf)
        source_ = std::make_unique<tvf::GltfSource>(
            tvf::loadGltfSource(data.data(), data.size(), f == tvf::MeshFormat::Glb));
    });
  }

  // '' when the model's own UVs serve as the flow map's atlas, else why not (then one is generated).
  std::string atlasNote() {
    std::string note;
    attempt(lastError_, [&] {
      const Mesh& m = need();
      note = m.surface.hasUVs() ? tvf::exportAtlasFor(m.surface, m.topology, {}, false).cornerUVs.empty()
                                      ? "its TEXCOORD_0 is not a one-to-one atlas"
                                      : ""
                                : "it has no texture coordinates (TEXCOORD_0)";
    });
    return note;
  }

  val flowMapPng(const val& oneForm, const std::string& options) {
    return produce([&] {
      const tvf::FieldExportOptions o = optionsFrom(options);
      const Mesh& m = need();
      return tvf::exportFlowMapPng(m.surface, m.topology,
                                   tvf::exportAtlasFor(m.surface, m.topology, o, true).cornerUVs,
                                   numbersOf<double>(oneForm), o);
    });
  }

  val glb(const val& oneForm, const std::string& design, const std::string& options, const val& texture) {
    return produce([&] {
      const tvf::FieldExportOptions o = optionsFrom(options);
      const Mesh& m = need();
      std::vector<uint8_t> baseColor;
      std::vector<float> phase;
      const tvf::ExportAtlas atlas = atlasFor(m, o, texture, baseColor, phase);
      return tvf::exportFieldGlb(m.surface, m.topology, geometry(), source_.get(), atlas,
                                 numbersOf<double>(oneForm),
                                 design.empty() ? nlohmann::json() : nlohmann::json::parse(design), o, baseColor,
                                 phase);
    });
  }

  val directionFlowMapPng(const val& faceDirections, int symmetry, const std::string& options) {
    return produce([&] {
      const tvf::FieldExportOptions o = optionsFrom(options);
      const Mesh& m = need();
      return tvf::exportDirectionFlowMapPng(m.surface, m.topology, geometry(),
                                            tvf::exportAtlasFor(m.surface, m.topology, o, true).cornerUVs,
                                            numbersOf<double>(faceDirections), symmetry, o);
    });
  }

  val directionGlb(const val& faceDirections, int symmetry, const std::string& design, const std::string& options,
                   const val& texture) {
    return produce([&] {
      const tvf::FieldExportOptions o = optionsFrom(options);
      const Mesh& m = need();
      std::vector<uint8_t> baseColor;
      std::vector<float> phase;
      const tvf::ExportAtlas atlas = atlasFor(m, o, texture, baseColor, phase);
      return tvf::exportDirectionGlb(m.surface, m.topology, geometry(), source_.get(), atlas,
                                     numbersOf<double>(faceDirections), symmetry,
                                     design.empty() ? nlohmann::json() : nlohmann::json::parse(design), o,
                                     baseColor, phase);
    });
  }

  // Directional's raw field text, or '' with lastError() set.
  std::string rawField(const val& faceDirections, int symmetry) {
    std::string text;
    attempt(lastError_, [&] {
      const std::vector<double> directions = numbersOf<double>(faceDirections);
      if (symmetry < 2 || directions.size() != 3 * static_cast<std::size_t>(need().surface.numFaces()))
        throw tvf::InputError("a raw field needs symmetry >= 2 and one direction per face");
      text = tvf::exportRawField(geometry(), directions, symmetry);
    });
    return text;
  }

  // The quad meshers' files, as `tvf export --sing/--rosy/--sharp` writes them from the same read-outs (the
  // Designer's singularities, face directions and feature edges): the same bytes.
  std::string singFile(int symmetry, const std::string& singularities) {
    return text([&] {
      std::vector<tvf::Singularity> list;
      for (const nlohmann::json& s : nlohmann::json::parse(singularities))
        list.push_back({s.at("vertex").get<int32_t>(), s.at("index").get<double>()});
      return tvf::writeSingFile(symmetry, list);
    });
  }

  std::string rosyFile(const val& faceDirections, int symmetry) {
    return text([&] {
      const std::vector<double> directions = numbersOf<double>(faceDirections);
      if (directions.size() != 3 * static_cast<std::size_t>(need().surface.numFaces()))
        throw tvf::InputError(".rosy: expected one direction per face");
      return tvf::writeRosyFile(directions, symmetry);
    });
  }

  // featureEdges: edge indices of the Designer's topology, which buildTopology makes the same from the same
  // welded mesh as this exporter's.
  std::string sharpFile(const val& featureEdges) {
    return text([&] {
      const Mesh& m = need();
      const std::vector<int32_t> edges = numbersOf<int32_t>(featureEdges);
      for (const int32_t e : edges)
        if (e < 0 || e >= m.topology.numEdges) throw tvf::InputError(".sharp: a feature edge names no edge");
      return tvf::writeSharpFile(m.topology, geometry(), m.surface.positions, edges);
    });
  }

  std::string lastError() const { return lastError_; }

 private:
  // The Designer's mesh with what the exports derive from it, each derived once per mesh: the topology when
  // it is set (every export reads it), the geometry on the first GLB (only its vertex vectors need it).
  struct Mesh {
    tvf::SurfaceMesh surface;
    tvf::MeshTopology topology;
    std::unique_ptr<tvf::MeshGeometry> geometry;
  };

  // The atlas a GLB uses: the export's own, or the texture's UVs when a texture goes with it. A texture
  // {stripes: {cornerPhase, branchIndex, families, profile, width?, light?, dark?}} is the page's stripe
  // pattern (design/design_stripes.h), drawn here into the export's atlas as `tvf export --stripes` draws it.
  static tvf::ExportAtlas atlasFor(const Mesh& m, const tvf::FieldExportOptions& o, const val& texture,
                                   std::vector<uint8_t>& baseColor, std::vector<float>& phaseTexcoords) {
    tvf::ExportAtlas atlas;
    if (isNullish(texture)) return tvf::exportAtlasFor(m.surface, m.topology, o, o.embedFlowMap);
    if (!isNullish(texture["stripes"])) {
      atlas = tvf::exportAtlasFor(m.surface, m.topology, o, true);
      const tvf::StripePattern pattern = stripePatternOf(m, texture["stripes"]);
      baseColor = stripePng(m, atlas, o, pattern, texture["stripes"]);
      phaseTexcoords = tvf::stripeTexcoords(m.surface, m.topology, pattern);
      return atlas;
    }
    baseColor = bytesOf(texture["png"]);
    atlas.cornerUVs = numbersOf<float>(texture["cornerUVs"]);
    if (baseColor.empty()) throw tvf::InputError("export: the texture has no image");
    if (atlas.cornerUVs.size() != 6 * static_cast<std::size_t>(m.surface.numFaces()))
      throw tvf::InputError("export: the texture needs 6 UV values per face of the mesh");
    // The model's own UVs fit the model's layout; any others need a vertex per (vertex, UV) pair.
    atlas.generated = atlas.cornerUVs != m.surface.cornerUVs;
    return atlas;
  }

  static tvf::StripePattern stripePatternOf(const Mesh& m, const val& stripes) {
    tvf::StripePattern pattern;
    pattern.families = stripes["families"].as<int>();
    pattern.cornerPhase = numbersOf<float>(stripes["cornerPhase"]);
    pattern.branchIndex = numbersOf<int8_t>(stripes["branchIndex"]);
    const std::size_t nF = static_cast<std::size_t>(m.surface.numFaces());
    if (pattern.families < 1 || pattern.families > 2 || pattern.cornerPhase.size() != 3 * nF * pattern.families ||
        pattern.branchIndex.size() != nF * pattern.families)
      throw tvf::InputError("export: the stripe pattern is not of this mesh");
    return pattern;
  }

  static std::vector<uint8_t> stripePng(const Mesh& m, const tvf::ExportAtlas& atlas, const tvf::FieldExportOptions& o,
                                        const tvf::StripePattern& pattern, const val& stripes) {
    tvf::StripeColours colours;
    colourOf(stripes["light"], colours.light);
    colourOf(stripes["dark"], colours.dark);
    const double width = stripes["width"].isNumber() ? stripes["width"].as<double>() : 0.0;
    const std::vector<uint8_t> rgba =
        tvf::stripeTextureRgba(m.surface, pattern, atlas.cornerUVs, o.size, o.gutterTexels, colours,
                               tvf::stripeProfileNamed(stripes["profile"].as<std::string>()), width);
    return tvf::encodePngRgba(std::vector<uint16_t>(rgba.begin(), rgba.end()), o.size, o.size, 8);
  }

  // [r, g, b] in 0..255, or nothing (the default stays).
  static void colourOf(const val& rgb, uint8_t out[3]) {
    const std::vector<double> c = numbersOf<double>(rgb);
    if (c.empty()) return;
    if (c.size() != 3) throw tvf::InputError("export: a stripe colour is [r, g, b]");
    for (int k = 0; k < 3; ++k) out[k] = static_cast<uint8_t>(std::clamp(std::lround(c[k]), 0L, 255L));
  }

  const Mesh& need() const {
    if (!mesh_) throw tvf::InputError("no mesh set for export");
    return *mesh_;
  }
  const tvf::MeshGeometry& geometry() {
    Mesh& m = *mesh_;
    if (!m.geometry)
      m.geometry = std::make_unique<tvf::MeshGeometry>(tvf::computeMeshGeometry(m.surface, m.topology));
    return *m.geometry;
  }
  template <typename F>
  static bool attempt(std::string& error, F&& f) {
    try {
      f();
      error.clear();
      return true;
    } catch (const tvf::InputError& e) {
      error = e.what();
    } catch (const nlohmann::json::exception& e) {
      error = std::string("invalid JSON: ") + e.what();
    } catch (const std::bad_alloc&) {
      error = "out of memory";
    } catch (const std::exception& e) {
      error = std::string("internal error: ") + e.what();
    }
    return false;
  }
  template <typename F>
  std::string run(F&& f) {
    attempt(lastError_, std::forward<F>(f));
    return lastError_;
  }
  template <typename F>
  std::string text(F&& f) {
    std::string out;
    attempt(lastError_, [&] { out = f(); });
    return out;
  }
  template <typename F>
  val produce(F&& f) {
    std::vector<uint8_t> bytes;
    if (!attempt(lastError_, [&] { bytes = f(); })) return val::null();
    return toUint8Array(bytes);
  }

  std::unique_ptr<Mesh> mesh_;
  std::unique_ptr<tvf::GltfSource> source_;
  std::string lastError_;
};

std::string embeddedDesignJson(const val& bytes) {
  try {
    const std::vector<uint8_t> data = bytesOf(bytes);
    return tvf::readEmbeddedDesign(data.data(), data.size()).dump();
  } catch (const std::exception&) {
    return "null";
  }
}

// A .sing file read (io/sing_file.h) as JSON: {symmetry, singularities: [{vertex, index}]}, or {error}.
std::string readSingJson(const std::string& text) {
  try {
    const tvf::SingFile file = tvf::readSingFile(text);
    nlohmann::json list = nlohmann::json::array();
    for (const tvf::Singularity& s : file.singularities)
      list.push_back({{"vertex", s.vertex}, {"index", s.index}});
    return nlohmann::json{{"symmetry", file.symmetry}, {"singularities", list}}.dump();
  } catch (const std::exception& e) {
    return nlohmann::json{{"error", e.what()}}.dump();
  }
}

}  // namespace

EMSCRIPTEN_BINDINGS(tvf_export) {
  emscripten::class_<FieldExporterBinding>("FieldExporter")
      .constructor<>()
      .function("setMesh", &FieldExporterBinding::setMesh)
      .function("setSource", &FieldExporterBinding::setSource)
      .function("atlasNote", &FieldExporterBinding::atlasNote)
      .function("flowMapPng", &FieldExporterBinding::flowMapPng)
      .function("glb", &FieldExporterBinding::glb)
      .function("directionFlowMapPng", &FieldExporterBinding::directionFlowMapPng)
      .function("directionGlb", &FieldExporterBinding::directionGlb)
      .function("rawField", &FieldExporterBinding::rawField)
      .function("singFile", &FieldExporterBinding::singFile)
      .function("rosyFile", &FieldExporterBinding::rosyFile)
      .function("sharpFile", &FieldExporterBinding::sharpFile)
      .function("lastError", &FieldExporterBinding::lastError);
  emscripten::function("embeddedDesignJson", &embeddedDesignJson);
  emscripten::function("readSingJson", &readSingJson);
}
