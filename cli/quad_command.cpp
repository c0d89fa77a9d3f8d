#include "cli/quad_command.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "cli/bench_timing.h"
#include "common/input_error.h"
#include "design/design_document.h"
#include "design/designer.h"
#include "io/mesh_io.h"
#include "io/polygon_obj.h"
#include "quad/quad_remesh.h"
#include "quad/quad_remesh_json.h"

namespace tvf::cli {
namespace {

double positiveNumber(const std::string& flag, const char* text) {
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != 0 || !std::isfinite(value) || !(value > 0))
    throw InputError(flag + " needs a positive number, got \"" + std::string(text) + "\"");
  return value;
}

void printTable(const nlohmann::json& s) {
  std::cout << "quads " << s["quads"] << " of " << s["faces"] << " faces, " << s["vertices"] << " vertices\n"
            << "irregular vertices " << s["irregularVertices"] << " (field singularities "
            << s["fieldSingularities"] << ")\nedge angle to the field: median " << s["edgeAngleMedianDeg"]
            << " deg, 90th percentile " << s["edgeAngleP90Deg"] << " deg\nHausdorff distance / diagonal "
            << s["hausdorffRelative"] << "\naspect ratio median " << s["aspectMedian"] << "\nflipped "
            << s["flippedFaces"] << ", degenerate " << s["degenerateFaces"] << "\ntime " << s["ms"]
            << " ms\n";
}

}  // namespace

int quadCommand(int argc, char** argv, const std::function<nlohmann::json(const std::string&)>& readDesign) {
  if (argc < 4)
    throw InputError("usage: tvf quad MESH DESIGN.json -o OUT.obj [--edge-length L | --quads N] [--json]");
  const std::string meshPath = argv[2], designPath = argv[3];
  std::string outPath;
  QuadRemeshOptions options;
  bool json = false;
  for (int i = 4; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json") {
      json = true;
    } else if (i + 1 >= argc) {
      throw InputError(a + ": unknown option or missing value");
    } else if (a == "-o") {
      outPath = argv[++i];
    } else if (a == "--edge-length") {
      options.edgeLength = positiveNumber(a, argv[++i]);
    } else if (a == "--quads") {
      const double n = positiveNumber(a, argv[++i]);
      if (n > 4e6) throw InputError("--quads: at most 4 million");
      options.targetQuads = static_cast<int64_t>(std::llround(n));
    } else {
      throw InputError(a + ": unknown option");
    }
  }
  if (outPath.empty()) throw InputError("tvf quad: give -o OUT.obj");
  if (options.edgeLength > 0 && options.targetQuads > 0)
    throw InputError("give --edge-length or --quads, not both");
  if (options.edgeLength == 0 && options.targetQuads == 0) options.targetQuads = 5000;
  Designer designer(loadMesh(meshPath));
  designer.setMetisOrdering(true);
  applyDesignDocument(designer, readDesign(designPath));
  if (designer.symmetry() != 4)
    throw InputError("Quad meshes need a cross field: the design has symmetry " +
                     std::to_string(designer.symmetry()) + " (set \"symmetry\": 4)");
  designer.solve();
  for (int32_t e : designer.featureEdges())
    for (int k = 0; k < 2; ++k) options.featureEdges.push_back(designer.topology().edgeVertices[2 * e + k]);
  const QuadRemeshResult r = quadRemesh(designer.mesh(), designer.topology(), designer.geometry(),
                                        designer.faceVectors(), designer.symmetry(), options);
  std::ofstream out(outPath, std::ios::binary);
  if (!(out << writePolygonObj(r.mesh, "tvf quad: " + std::to_string(r.stats.quads) + " quads")))
    throw InputError("cannot write " + outPath);
  const nlohmann::json stats = quadRemeshJson(r);
  if (json)
    std::cout << stats.dump() << "\n";
  else
    printTable(stats);
  return 0;
}

nlohmann::json quadBench(const std::string& meshPath, int64_t quads, int repeat) {
  Designer designer(loadMesh(meshPath));
  designer.setMetisOrdering(true);
  designer.setSymmetry(4);
  designer.solve();
  QuadRemeshOptions options;
  options.targetQuads = quads;
  std::vector<std::vector<double>> times(5);
  nlohmann::json last;
  for (int r = 0; r < repeat; ++r) {
    const QuadRemeshResult q = quadRemesh(designer.mesh(), designer.topology(), designer.geometry(),
                                          designer.faceVectors(), 4, options);
    const double ms[5] = {q.totalMs, q.cutMs, q.parametrizeMs, q.extractMs, q.measureMs};
    for (int k = 0; k < 5; ++k) times[k].push_back(ms[k]);
    last = quadRemeshJson(q);
  }
  return {{"mesh", meshPath},
          {"faces", designer.topology().numFaces},
          {"targetQuads", quads},
          {"repeat", repeat},
          {"quadMs", median(times[0])},
          {"stageMs",
           {{"cut", median(times[1])},
            {"parametrize", median(times[2])},
            {"extract", median(times[3])},
            {"measure", median(times[4])}}},
          {"stats", last}};
}

}  // namespace tvf::cli
