// tvf: the field-design core from the command line (info, design, bench).
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "cli/bench.h"
#include "design/design_document.h"
#include "design/mesh_info.h"
#include "io/mesh_io.h"

namespace {

constexpr int kUsageError = 2;

int usage() {
  std::cerr << "usage:\n"
               "  tvf info MESH\n"
               "  tvf design MESH DESIGN.json [-o FIELD.json]\n"
               "  tvf bench MESH [--repeat N] [--gamma G] [--amd | --metis | --compare] [--json]\n"
               "Fill-reducing ordering: METIS nested dissection by default (less fill, faster solves and\n"
               "updates, slower analysis), as in the browser build; --amd for AMD; --compare for both,\n"
               "interleaved repeat by repeat in one process (JSON only).\n"
               "MESH: .gltf, .glb, .off, .obj or .ply\n";
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

int design(const std::string& meshPath, const std::string& designPath, const std::string& outPath) {
  tvf::Designer designer(tvf::loadMesh(meshPath));
  designer.setMetisOrdering(true);
  tvf::applyDesignDocument(designer, readJsonFile(designPath));
  designer.solve();
  const std::string text = tvf::fieldDocument(designer).dump();
  if (outPath.empty()) {
    std::cout << text << "\n";
  } else {
    std::ofstream out(outPath);
    if (!(out << text << "\n")) throw tvf::InputError("cannot write " + outPath);
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
  std::vector<bool> orderings{true};
  for (int k = 3; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--repeat" && k + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++k]));
    } else if (a == "--gamma" && k + 1 < argc) {
      gamma = std::atof(argv[++k]);
    } else if (a == "--json") {
      json = true;
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
  const nlohmann::json r = tvf::runBench(argv[2], repeat, gamma, orderings);
  if (json)
    std::cout << r.dump() << "\n";
  else
    printBenchTable(r);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return usage();
  const std::string command = argv[1];
  try {
    if (command == "info" && argc == 3) return info(argv[2]);
    if (command == "design" && (argc == 4 || (argc == 6 && std::strcmp(argv[4], "-o") == 0)))
      return design(argv[2], argv[3], argc == 6 ? argv[5] : "");
    if (command == "bench") return bench(argc, argv);
    return usage();
  } catch (const tvf::InputError& e) {
    std::cerr << "tvf: " << e.what() << "\n";
    return kUsageError;
  } catch (const std::exception& e) {
    std::cerr << "tvf: internal error: " << e.what() << "\n";
    return 1;
  }
}
