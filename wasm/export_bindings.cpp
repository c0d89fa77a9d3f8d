// SPDX-License-Identifier: GPL-2.0-or-later
//
// embind bindings of the exporters (core/design/field_export.h): the page's export buttons produce the
// same bytes as `tvf export` for the same mesh file and one-form. Same conventions as bindings.cpp: nothing
// throws into JS (failures return null or '' and leave the message in lastError()).
//
//   const x = new Module.FieldExporter();
//   x.load(uint8Array, 'glb')                 // '' or an error message; keeps a glTF document for re-export
//   x.atlasNote()                             // '' when the model's own UVs are the atlas, else why not
//                                             // (then exports generate one: texture/texture_atlas.h)
//   x.flowMapPng(oneForm, optionsJson)        // Uint8Array (a copy) or null
//   x.glb(oneForm, designJson, optionsJson, baseColorPng)   // Uint8Array or null; designJson may be ''
//   x.lastError(), x.delete()
//   Module.embeddedDesignJson(uint8Array)     // the design a GLB carries, 'null' when none
// optionsJson: {size, convention: 'gltf'|'opengl', bits: 8|16, gutter, strength, rotation, embedFlowMap,
// embedDesign}; every key optional (defaults as the CLI's).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "design/field_export.h"
#include "io/gltf_writer.h"
#include "io/mesh_io.h"

namespace {

using emscripten::val;

std::vector<uint8_t> bytesOf(const val& array) {
  const bool buffer = array.instanceof (val::global("ArrayBuffer"));
  return emscripten::convertJSArrayToNumberVector<uint8_t>(buffer ? val::global("Uint8Array").new_(array)
                                                                  : array);
}

val toUint8Array(const std::vector<uint8_t>& bytes) {
  // A copy: a view into wasm memory would go stale on the next allocation.
  return val::global("Uint8Array").new_(val(emscripten::typed_memory_view(bytes.size(), bytes.data())));
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
  std::string load(const val& bytes, const std::string& format) {
    return run([&] {
      const std::vector<uint8_t> data = bytesOf(bytes);
      if (data.empty()) throw tvf::InputError("the mesh file is empty");
      tvf::MeshFormat f = tvf::formatFromBytes(data.data(), data.size());
      if (!format.empty()) f = tvf::formatFromPath("model." + format);
      auto mesh = std::make_unique<tvf::SurfaceMesh>(tvf::loadMeshFromMemory(data.data(), data.size(), f));
      std::unique_ptr<tvf::GltfSource> source;
      if (f == tvf::MeshFormat::Glb || f == tvf::MeshFormat::Gltf)
        source = std::make_unique<tvf::GltfSource>(
            tvf::loadGltfSource(data.data(), data.size(), f == tvf::MeshFormat::Glb));
      mesh_ = std::move(mesh);
      source_ = std::move(source);
    });
  }

  // '' when the model's own UVs serve as the flow map's atlas, else why not (then one is generated).
  std::string atlasNote() {
    std::string note;
    attempt(lastError_, [&] {
      note = need().hasUVs() ? tvf::exportAtlasFor(need(), {}, false).cornerUVs.empty()
                                   ? "its TEXCOORD_0 is not a one-to-one atlas"
                                   : ""
                             : "it has no texture coordinates (TEXCOORD_0)";
    });
    return note;
  }

  val flowMapPng(const val& oneForm, const std::string& options) {
    return produce([&] {
      const tvf::FieldExportOptions o = optionsFrom(options);
      return tvf::exportFlowMapPng(need(), tvf::exportAtlasFor(need(), o, true).cornerUVs, numbers(oneForm),
                                   o);
    });
  }

  val glb(const val& oneForm, const std::string& design, const std::string& options,
          const val& baseColorPng) {
    return produce([&] {
      const tvf::FieldExportOptions o = optionsFrom(options);
      const std::vector<uint8_t> baseColor = baseColorPng.isNull() || baseColorPng.isUndefined()
                                                 ? std::vector<uint8_t>{}
                                                 : bytesOf(baseColorPng);
      return tvf::exportFieldGlb(
          need(), source_.get(), tvf::exportAtlasFor(need(), o, o.embedFlowMap), numbers(oneForm),
          design.empty() ? nlohmann::json() : nlohmann::json::parse(design), o, baseColor);
    });
  }

  std::string lastError() const { return lastError_; }

 private:
  const tvf::SurfaceMesh& need() const {
    if (!mesh_) throw tvf::InputError("no mesh loaded for export");
    return *mesh_;
  }
  static std::vector<double> numbers(const val& array) {
    return emscripten::convertJSArrayToNumberVector<double>(array);
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
  val produce(F&& f) {
    std::vector<uint8_t> bytes;
    if (!attempt(lastError_, [&] { bytes = f(); })) return val::null();
    return toUint8Array(bytes);
  }

  std::unique_ptr<tvf::SurfaceMesh> mesh_;
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

}  // namespace

EMSCRIPTEN_BINDINGS(tvf_export) {
  emscripten::class_<FieldExporterBinding>("FieldExporter")
      .constructor<>()
      .function("load", &FieldExporterBinding::load)
      .function("atlasNote", &FieldExporterBinding::atlasNote)
      .function("flowMapPng", &FieldExporterBinding::flowMapPng)
      .function("glb", &FieldExporterBinding::glb)
      .function("lastError", &FieldExporterBinding::lastError);
  emscripten::function("embeddedDesignJson", &embeddedDesignJson);
}
