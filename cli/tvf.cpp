// tvf: the field-design core from the command line (info, design, bench).
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "cli/bench.h"
#include "cli/ordering_cache.h"
#include "cli/quad_command.h"
#include "design/design_document.h"
#include "design/design_stripes.h"
#include "design/field_export.h"
#include "design/mesh_info.h"
#include "direction/stripe_texture.h"
#include "io/gltf_writer.h"
#include "io/mesh_io.h"
#include "io/png_writer.h"
#include "io/rosy_file.h"
#include "io/sharp_file.h"
#include "io/sing_file.h"

namespace {

constexpr int kUsageError = 2;

int usage() {
  std::cerr
      << "usage:\n"
         "  tvf info MESH\n"
         "  tvf design MESH DESIGN.json [-o FIELD.json] [--ignore-fingerprint] [--hodge]\n"
         "             [--sing IN.sing] [--ordering-cache DIR]\n"
         "  tvf export MESH DESIGN.json [--glb OUT.glb] [--flowmap OUT.png] [--size N]\n"
         "             [--convention gltf|opengl] [--bits 8|16] [--strength S] [--rotation RADIANS]\n"
         "             [--no-embed-flowmap] [--component whole|exact|coexact|harmonic]\n"
         "             [--rawfield OUT.rawfield] [--sing OUT.sing] [--rosy OUT.rosy]\n"
         "             [--sharp OUT.sharp] [--stripes FREQ] [--stripe-profile NAME] [--stripe-width W]\n"
         "             [--stripes-across]\n"
         "             [--ordering-cache DIR]\n"
         "  tvf quad MESH DESIGN.json -o OUT.obj [--edge-length L | --quads N] [--json]\n"
         "  tvf bench MESH [--repeat N] [--gamma G] [--amd | --metis | --compare] [--json]\n"
         "            [--threads N] [--symmetry N] [--scaling]\n"
         "  tvf bench MESH --quads N [--repeat R]   (the quad remesher, JSON)\n"
         "--ordering-cache DIR keeps the field's fill-reducing ordering and symbolic factor in DIR, one\n"
         "file per mesh and symmetry: the same mesh again skips the analysis (a stale or foreign file\n"
         "is ignored).\n"
         "Fill-reducing ordering: METIS nested dissection by default (less fill, faster solves and\n"
         "updates, slower analysis), as in the browser build; --amd for AMD; --compare for both,\n"
         "interleaved repeat by repeat in one process (JSON only).\n"
         "--threads: threads of the numeric factorization and of each solve's backward substitution\n"
         "(default: the cores, up to 16); with more than one, the JSON compares the field with one\n"
         "thread's (parallelFieldDifference) beside the other ordering's (orderingFieldDifference).\n"
         "MESH: .gltf, .glb, .off, .obj or .ply\n"
         "A design saved for another mesh (its \"mesh\" fingerprint differs) is refused unless\n"
         "--ignore-fingerprint is given.\n"
         "--hodge: the field file gets \"hodge\" (Hodge decomposition: exact, coexact, harmonic,\n"
         "potentials, energyShares). --component: export that part of the field instead of the whole.\n"
         "A design's \"symmetry\" (1 vector, 2 line, 4 cross field; up to 6) makes design write\n"
         "faceDirections (one unit representative per face) and fractional singularity indices;\n"
         "bench --symmetry N times that field's system; bench --scaling times only the factorization,\n"
         "solves, updates and strokes (scripts/bench-cores.sh). export of such a design combs the\n"
         "directions per atlas chart for the flow map and the GLB (KHR_materials_anisotropy, _FIELD);\n"
         "--rawfield writes all N directions per face in Directional's raw field format\n"
         "(docs/export.md).\n"
         "Prescribed singularities and sharp features: a design's \"singularities\",\n"
         "\"featureAngle\" and \"featureEdges\" (docs/design-format.md). design --sing adds a\n"
         "Directional .sing file's singularities to the design's (the file's N is the symmetry of\n"
         "a design that names none). export --sing writes the field's singularities (Directional),\n"
         "--rosy the cross field (QuadWild; symmetry 4), --sharp the feature edges (QuadWild).\n"
         "export --stripes FREQ bakes the field's stripe pattern (FREQ stripes per unit length) into the\n"
         "GLB's base colour over the export's atlas (docs/export.md); --stripe-profile stripes, wood,\n"
         "grid, bricks or weave (default: stripes, grid for a cross field); --stripe-width W the lines'\n"
         "width as a share of a period, in (0, 1] (default: the profile's own, 1/2 for stripes);\n"
         "--stripes-across turns a vector or line field's stripes across it (a two-family profile's\n"
         "families swap). On a surface with a handle or a tube a vector or line field's frequency is\n"
         "fitted within 5 % so that whole stripes go round its loops (docs/stripes.md).\n"
         "quad: a quad mesh following the design's cross field (symmetry 4; a closed surface), at an\n"
         "edge length or about N quads (default 5000), as OBJ; --json prints its statistics\n"
         "(docs/quad-meshes.md).\n";
  return kUsageError;
}

nlohmann::json readJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw tvf::InputError("cannot open " + path);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw tvf::InputError(path + " is not valid JSON: " + e.what());
  }
}

int info(const std::string& path) {
  const nlohmann::json report = tvf::meshInfoJson(tvf::loadMesh(path));
  if (!report.contains("edges")) {
    std::cerr << "tvf: " << path << ": " << report["problems"][0].get<std::string>() << "\n";
    return kUsageError;
  }
  std::cout << report.dump(2) << "\n";
  return 0;
}

// A field of directions rather than a 1-form: symmetry N >= 2, or any N with prescribed singularities (they
// make even N = 1 a unit direction field; design/designer.h).
bool directionField(const tvf::Designer& designer) {
  if (designer.symmetry() != 1) return true;
  for (const tvf::ConstraintSpec& s : designer.constraints())
    if (s.kind == tvf::ConstraintKind::Singularity) return true;
  return false;
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw tvf::InputError("cannot open " + path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeTextFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (!(out << text)) throw tvf::InputError("cannot write " + path);
}

// Directional's .sing added to the design's "singularities": the file's N becomes the design's symmetry when
// the design names none; otherwise each index k/N must fit the design's symmetry (applyDesignDocument
// checks).
void addSingFile(nlohmann::json& design, const std::string& singPath) {
  tvf::SingFile file;
  try {
    file = tvf::readSingFile(readTextFile(singPath));
  } catch (const tvf::InputError& e) {
    throw tvf::InputError(singPath + ": " + e.what());
  }
  if (!design.is_object()) return;  // applyDesignDocument names the problem
  if (!design.contains("symmetry") && file.symmetry != 1) design["symmetry"] = file.symmetry;
  nlohmann::json& list = design["singularities"];
  if (list.is_null()) list = nlohmann::json::array();
  if (!list.is_array()) return;
  for (const auto& s : file.singularities) list.push_back({{"vertex", s.vertex}, {"index", s.index}});
}

// --ordering-cache DIR around the designer's first solve (ordering_cache.h); a cache file ignored is said on
// stderr.
void solveWithOrderingCache(tvf::Designer& designer, const std::string& cacheDir) {
  if (cacheDir.empty()) return designer.solve();
  const std::string adopted = tvf::adoptCachedOrdering(designer, cacheDir);
  if (adopted != "adopted" && adopted != "none kept")
    std::cerr << "tvf: --ordering-cache: " << adopted << "\n";
  designer.solve();
  tvf::keepOrdering(designer, cacheDir);
}

int design(const std::string& meshPath, const std::string& designPath, const std::string& outPath,
           bool checkFingerprint, bool hodge, const std::string& singPath, const std::string& cacheDir) {
  tvf::Designer designer(tvf::loadMesh(meshPath));
  designer.setMetisOrdering(true);
  nlohmann::json document = readJsonFile(designPath);
  if (!singPath.empty()) addSingFile(document, singPath);
  try {
    tvf::applyDesignDocument(designer, document, checkFingerprint);
  } catch (const tvf::InputError& e) {
    const std::string why = e.what();
    throw tvf::InputError(
        designPath + ": " + why +
        (why.find("another mesh") != std::string::npos ? " (--ignore-fingerprint applies it anyway)" : ""));
  }
  solveWithOrderingCache(designer, cacheDir);
  nlohmann::json field = tvf::fieldDocument(designer);
  if (hodge && directionField(designer))
    throw tvf::InputError(
        "--hodge: the Hodge decomposition is of vector fields (symmetry 1, no prescribed singularity); this "
        "design has symmetry " +
        std::to_string(designer.symmetry()) + (designer.symmetry() == 1 ? " and singularities" : ""));
  if (hodge) field["hodge"] = tvf::hodgeDocument(designer.hodgeDecomposition());
  const std::string text = field.dump();
  if (outPath.empty()) {
    std::cout << text << "\n";
  } else {
    std::ofstream out(outPath);
    if (!(out << text << "\n")) throw tvf::InputError("cannot write " + outPath);
  }
  return 0;
}

int designCommand(int argc, char** argv) {
  std::string out, sing, cacheDir;
  bool checkFingerprint = true, hodge = false;
  for (int k = 4; k < argc; ++k) {
    if (std::strcmp(argv[k], "-o") == 0 && k + 1 < argc)
      out = argv[++k];
    else if (std::strcmp(argv[k], "--ordering-cache") == 0 && k + 1 < argc)
      cacheDir = argv[++k];
    else if (std::strcmp(argv[k], "--sing") == 0 && k + 1 < argc)
      sing = argv[++k];
    else if (std::strcmp(argv[k], "--ignore-fingerprint") == 0)
      checkFingerprint = false;
    else if (std::strcmp(argv[k], "--hodge") == 0)
      hodge = true;
    else
      return usage();
  }
  return design(argv[2], argv[3], out, checkFingerprint, hodge, sing, cacheDir);
}

std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw tvf::InputError("cannot open " + path);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  if (!out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
    throw tvf::InputError("cannot write " + path);
}

// DESIGN.json, or a GLB/glTF this tool exported (its embedded design).
nlohmann::json readDesign(const std::string& path) {
  const tvf::MeshFormat format =
      path.size() > 5 && (path.substr(path.size() - 4) == ".glb" || path.substr(path.size() - 5) == ".gltf")
          ? tvf::MeshFormat::Glb
          : tvf::MeshFormat::Off;
  if (format != tvf::MeshFormat::Glb) return readJsonFile(path);
  const std::vector<uint8_t> bytes = readBytes(path);
  nlohmann::json design = tvf::readEmbeddedDesign(bytes.data(), bytes.size());
  if (design.is_null()) throw tvf::InputError(path + " holds no design (not exported by tvf or the page)");
  return design;
}

double numberArgument(const std::string& flag, const char* text) {
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != 0 || !std::isfinite(value))
    throw tvf::InputError(flag + " needs a number, got \"" + std::string(text) + "\"");
  return value;
}

// The quad-meshing tools' files (docs/export.md): Directional's .sing (the field's singularities, prescribed
// and free alike, so that index prescription there reproduces this field's), QuadWild's .rosy and .sharp.
void writeInteropFiles(const tvf::Designer& designer, const std::string& singPath,
                       const std::string& rosyPath, const std::string& sharpPath) {
  if (!singPath.empty())
    writeTextFile(singPath, tvf::writeSingFile(designer.symmetry(), designer.singularities()));
  if (!rosyPath.empty())
    writeTextFile(rosyPath, tvf::writeRosyFile(designer.faceVectors(), designer.symmetry()));
  if (!sharpPath.empty())
    writeTextFile(sharpPath, tvf::writeSharpFile(designer.topology(), designer.geometry(),
                                                 designer.mesh().positions, designer.featureEdges()));
}

// The design's stripe pattern (design/design_stripes.h) baked for the GLB: drawn into the export's atlas as a
// PNG, and its phase as a texture coordinate (io/gltf_writer.h).
struct BakedStripes {
  std::vector<uint8_t> png;
  std::vector<float> phaseTexcoords;
};

BakedStripes bakeStripes(const tvf::Designer& designer, const tvf::ExportAtlas& atlas,
                         const tvf::FieldExportOptions& options, const tvf::DesignStripeOptions& stripes) {
  if (tvf::fieldIsZero(designer.vertexVectors()))
    throw tvf::InputError(
        "--stripes: the field is zero everywhere (the design has nothing to shape it): there is no direction "
        "for stripes to follow");
  tvf::DesignStripes pattern;
  pattern.compute(designer.mesh(), designer.topology(), designer.geometry(), designer.vertexNormals(),
                  designer.symmetry(), designer.vertexVectors(), stripes, &designer.faceVectors());
  if (pattern.pattern().loopFit != 1)  // the frequency drawn is not the one asked for: say so
    std::cerr << "tvf: --stripes: " << stripes.frequency * pattern.pattern().loopFit
              << " stripes per unit, fitted so that whole stripes go round the surface's loops\n";
  const std::vector<uint8_t> rgba =
      tvf::stripeTextureRgba(designer.mesh(), pattern.pattern(), atlas.cornerUVs, options.size,
                             options.gutterTexels, {}, stripes.profile, stripes.width);
  return {tvf::encodePngRgba(std::vector<uint16_t>(rgba.begin(), rgba.end()), options.size, options.size, 8),
          tvf::stripeTexcoords(designer.mesh(), designer.topology(), pattern.pattern())};
}

int exportCommand(int argc, char** argv) {
  if (argc < 4) return usage();
  const std::string meshPath = argv[2], designPath = argv[3];
  std::string glbPath, flowMapPath, rawFieldPath, singPath, rosyPath, sharpPath, cacheDir;
  tvf::FieldExportOptions options;
  tvf::FieldComponent component = tvf::FieldComponent::Whole;
  double stripes = 0;
  std::string stripeProfile;
  double stripeWidth = 0;
  bool stripesAcross = false;
  for (int k = 4; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--no-embed-flowmap") {
      options.embedFlowMap = false;
      continue;
    }
    if (a == "--stripes-across") {
      stripesAcross = true;
      continue;
    }
    if (k + 1 >= argc) return usage();
    const char* value = argv[++k];
    if (a == "--glb") {
      glbPath = value;
    } else if (a == "--flowmap") {
      flowMapPath = value;
    } else if (a == "--rawfield") {
      rawFieldPath = value;
    } else if (a == "--sing") {
      singPath = value;
    } else if (a == "--ordering-cache") {
      cacheDir = value;
    } else if (a == "--rosy") {
      rosyPath = value;
    } else if (a == "--sharp") {
      sharpPath = value;
    } else if (a == "--size") {
      options.size = static_cast<int>(numberArgument(a, value));
    } else if (a == "--convention") {
      options.convention = tvf::flowMapConventionFromName(value);
    } else if (a == "--bits") {
      options.bits = static_cast<int>(numberArgument(a, value));
      if (options.bits != 8 && options.bits != 16) throw tvf::InputError("--bits must be 8 or 16");
    } else if (a == "--strength") {
      options.anisotropyStrength = numberArgument(a, value);
    } else if (a == "--rotation") {
      options.anisotropyRotation = numberArgument(a, value);
    } else if (a == "--component") {
      component = tvf::fieldComponentFromName(value);
    } else if (a == "--stripes") {
      stripes = numberArgument(a, value);
      if (!(stripes > 0))
        throw tvf::InputError(
            "--stripes: the frequency must be a positive number of stripes per unit length");
    } else if (a == "--stripe-width") {
      stripeWidth = numberArgument(a, value);
      if (!(stripeWidth > 0 && stripeWidth <= 1))
        throw tvf::InputError("--stripe-width: the lines' width is a share of a period, in (0, 1]");
    } else if (a == "--stripe-profile") {
      stripeProfile = tvf::stripeProfileName(tvf::stripeProfileNamed(value));
    } else {
      return usage();
    }
  }
  if (glbPath.empty() && flowMapPath.empty() && rawFieldPath.empty() && singPath.empty() &&
      rosyPath.empty() && sharpPath.empty())
    throw tvf::InputError(
        "nothing to export: give --glb, --flowmap, --rawfield, --sing, --rosy and/or --sharp");
  const tvf::MeshFormat format = tvf::formatFromPath(meshPath);
  tvf::Designer designer(tvf::loadMesh(meshPath));
  designer.setMetisOrdering(true);
  tvf::applyDesignDocument(designer, readDesign(designPath));
  const int symmetry = designer.symmetry();
  const bool directions = directionField(designer);
  if (directions && component != tvf::FieldComponent::Whole)
    throw tvf::InputError(
        "--component: the Hodge decomposition is of vector fields (symmetry 1, no prescribed singularity); "
        "this design has symmetry " +
        std::to_string(symmetry) + (symmetry == 1 ? " and singularities" : ""));
  if (stripes > 0 && glbPath.empty())
    throw tvf::InputError("--stripes bakes the stripes into the GLB's base colour: give --glb too");
  if (!stripeProfile.empty() && !(stripes > 0))
    throw tvf::InputError("--stripe-profile draws the stripes of --stripes FREQ: give --stripes too");
  if (stripeWidth > 0 && !(stripes > 0))
    throw tvf::InputError("--stripe-width draws the stripes of --stripes FREQ: give --stripes too");
  if (stripesAcross && !(stripes > 0))
    throw tvf::InputError("--stripes-across turns the stripes of --stripes FREQ: give --stripes too");
  tvf::DesignStripeOptions stripeOptions;
  if (stripes > 0) {
    nlohmann::json o{{"frequency", stripes}};
    if (!stripeProfile.empty()) o["profile"] = stripeProfile;
    if (stripeWidth > 0) o["width"] = stripeWidth;
    if (stripesAcross) o["across"] = true;
    stripeOptions = tvf::designStripeOptionsFromJson(o.dump(), symmetry);
    tvf::checkStripeOptions(symmetry, stripeOptions);  // before the solve: a refusal costs nothing
  }
  if (!rosyPath.empty() && symmetry != 4)
    throw tvf::InputError("--rosy: .rosy holds a cross field (symmetry 4); this design has symmetry " +
                          std::to_string(symmetry));
  solveWithOrderingCache(designer, cacheDir);
  if (!rawFieldPath.empty()) {
    if (!directions)
      throw tvf::InputError(
          "--rawfield: a raw field holds line or cross fields; this design is a vector field "
          "(symmetry 1)");
    const std::string text = tvf::exportRawField(designer.geometry(), designer.faceVectors(), symmetry);
    writeBytes(rawFieldPath, std::vector<uint8_t>(text.begin(), text.end()));
  }
  writeInteropFiles(designer, singPath, rosyPath, sharpPath);
  if (glbPath.empty() && flowMapPath.empty()) return 0;
  // The whole field, or one part of its Hodge decomposition; the GLB still embeds the whole design.
  const std::vector<double> oneForm = directions ? std::vector<double>{}
                                      : component == tvf::FieldComponent::Whole
                                          ? designer.oneForm()
                                          : tvf::componentOneForm(designer.hodgeDecomposition(), component);
  const tvf::SurfaceMesh& mesh = designer.mesh();
  const tvf::ExportAtlas atlas =
      tvf::exportAtlasFor(mesh, designer.topology(), options,
                          !flowMapPath.empty() || (!glbPath.empty() && options.embedFlowMap) || stripes > 0);
  if (atlas.generated) {
    std::cerr << "tvf: " << meshPath << ": " << atlas.reason << "; using a generated atlas"
              << (glbPath.empty()
                      ? ""
                      : " (the GLB is rebuilt on it; --no-embed-flowmap keeps the model's layout)")
              << "\n";
  }
  if (!flowMapPath.empty()) {
    writeBytes(flowMapPath, !directions ? tvf::exportFlowMapPng(mesh, designer.topology(), atlas.cornerUVs,
                                                                oneForm, options)
                                        : tvf::exportDirectionFlowMapPng(
                                              mesh, designer.topology(), designer.geometry(), atlas.cornerUVs,
                                              designer.faceVectors(), symmetry, options));
  }
  if (!glbPath.empty()) {
    const BakedStripes baked =
        stripes > 0 ? bakeStripes(designer, atlas, options, stripeOptions) : BakedStripes{};
    std::unique_ptr<tvf::GltfSource> source;
    if (format == tvf::MeshFormat::Gltf || format == tvf::MeshFormat::Glb) {
      const std::vector<uint8_t> bytes = readBytes(meshPath);
      const std::string parent = std::filesystem::path(meshPath).parent_path().string();
      source = std::make_unique<tvf::GltfSource>(
          tvf::loadGltfSource(bytes.data(), bytes.size(), format == tvf::MeshFormat::Glb,
                              parent.empty() ? "." : parent, meshPath));
    }
    writeBytes(glbPath, !directions
                            ? tvf::exportFieldGlb(mesh, designer.topology(), designer.geometry(),
                                                  source.get(), atlas, oneForm, tvf::designDocument(designer),
                                                  options, baked.png, baked.phaseTexcoords)
                            : tvf::exportDirectionGlb(mesh, designer.topology(), designer.geometry(),
                                                      source.get(), atlas, designer.faceVectors(), symmetry,
                                                      tvf::designDocument(designer), options, baked.png,
                                                      baked.phaseTexcoords));
  }
  return 0;
}

void printBenchTable(const nlohmann::json& r) {
  std::cout << std::fixed << std::setprecision(2);
  std::cout << "| mesh | E | nnz/row M | nnz/row L | analyze ms | factor ms | solve ms | update ms | "
               "50-edge stroke+solve ms | reconstruct ms |\n|---|---|---|---|---|---|---|---|---|---|\n";
  std::cout << "| " << r["mesh"].get<std::string>() << " | " << r["edges"] << " | "
            << r["nnzPerRowM"].get<double>() << " | " << r["nnzPerRowL"].get<double>() << " | "
            << r["analyzeMs"].get<double>() << " | " << r["factorMs"].get<double>() << " | "
            << r["solveMs"].get<double>() << " | " << std::setprecision(3) << r["updateMs"].get<double>()
            << " | " << std::setprecision(2) << r["strokeUpdateSolveMs"].get<double>() << " | "
            << r["reconstructMs"].get<double>() << " |\n";
}

int bench(int argc, char** argv) {
  int repeat = 5;
  double gamma = 0;
  bool json = false;
  int threads = 0, symmetry = 1;
  int64_t quads = 0;
  bool scaling = false;
  std::vector<bool> orderings{true};
  for (int k = 3; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--repeat" && k + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++k]));
    } else if (a == "--gamma" && k + 1 < argc) {
      gamma = std::atof(argv[++k]);
    } else if (a == "--json") {
      json = true;
    } else if (a == "--threads" && k + 1 < argc) {
      threads = std::atoi(argv[++k]);
      if (threads < 1) throw tvf::InputError("--threads must be a whole number of at least 1");
    } else if (a == "--symmetry" && k + 1 < argc) {
      symmetry = std::atoi(argv[++k]);
      if (symmetry < 1 || symmetry > 6)
        throw tvf::InputError("--symmetry must be a whole number from 1 to 6");
    } else if (a == "--quads" && k + 1 < argc) {
      quads = std::atoll(argv[++k]);
      if (quads < 1 || quads > 4000000)
        throw tvf::InputError("--quads must be a whole number from 1 to 4000000");
    } else if (a == "--scaling") {
      scaling = true;
    } else if (a == "--metis") {
      orderings = {true};
    } else if (a == "--amd") {
      orderings = {false};
    } else if (a == "--compare") {
      orderings = {true, false};
      json = true;
    } else {
      return usage();
    }
  }
  if (quads > 0) {
    std::cout << tvf::cli::quadBench(argv[2], quads, repeat).dump() << "\n";
    return 0;
  }
  const nlohmann::json r = tvf::runBench(argv[2], repeat, gamma, orderings, threads, symmetry, scaling);
  if (json)
    std::cout << r.dump() << "\n";
  else
    printBenchTable(r);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // A fixed threshold for mapping big blocks: glibc raises it to the size of each mapped block freed, after
  // which a factor's arrays come from the reused heap instead, and a second factorization of armadillo-sub2
  // in one process took about twice the first (1,187 against 2,262-2,624 ms, medians of three; 1,224 with
  // this).
  mallopt(M_MMAP_THRESHOLD, 4 << 20);
#endif
  if (argc < 3) return usage();
  const std::string command = argv[1];
  try {
    if (command == "info" && argc == 3) return info(argv[2]);
    if (command == "design" && argc >= 4) return designCommand(argc, argv);
    if (command == "bench") return bench(argc, argv);
    if (command == "export") return exportCommand(argc, argv);
    if (command == "quad") return tvf::cli::quadCommand(argc, argv, readDesign);
    return usage();
  } catch (const tvf::InputError& e) {
    std::cerr << "tvf: " << e.what() << "\n";
    return kUsageError;
  } catch (const std::exception& e) {
    std::cerr << "tvf: internal error: " << e.what() << "\n";
    return 1;
  }
}
