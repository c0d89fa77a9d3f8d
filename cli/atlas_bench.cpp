// SPDX-License-Identifier: GPL-2.0-or-later
// tvf_atlas_bench: the generated texture atlas measured on meshes, one JSON object per mesh and resolution
// (generation time as the median over --repeat runs; `hash` of its UVs and charts, to compare two builds).
//   tvf_atlas_bench MESH... [--resolution N|auto]... [--gutter G] [--repeat N]
// 'auto' is the page's default resolution (web/synthesis/index.js defaultResolution: 256-1024 by face count).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/mesh_io.h"
#include "io/png_writer.h"
#include "texture/texture_atlas.h"

namespace {

int pageDefaultResolution(int32_t numFaces) {
  const double want = std::sqrt(numFaces * 16 / 0.6);
  int r = 256;
  while (r < want && r < 1024) r *= 2;
  return r;
}

// FNV-1a over the atlas's corner UVs and charts: two builds made the same atlas when their hashes agree.
std::string atlasHash(const tvf::TextureAtlas& atlas) {
  uint64_t h = 1469598103934665603ull;
  const auto add = [&](const void* data, size_t bytes) {
    for (size_t i = 0; i < bytes; ++i)
      h = (h ^ static_cast<const unsigned char*>(data)[i]) * 1099511628211ull;
  };
  add(atlas.cornerUVs.data(), atlas.cornerUVs.size() * sizeof(float));
  add(atlas.faceChart.data(), atlas.faceChart.size() * sizeof(int32_t));
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

// The atlas as an image: each chart's covered texels in a colour of its own, the rest black.
void writeChartImage(const tvf::TextureAtlas& atlas, const std::string& path) {
  const int n = atlas.resolution;
  std::vector<uint16_t> rgba(4 * static_cast<size_t>(n) * n, 0);
  for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
  for (size_t f = 0; f < atlas.faceChart.size(); ++f) {
    const int32_t c = atlas.faceChart[f];
    if (c < 0) continue;
    std::vector<float> one(atlas.cornerUVs.begin() + 6 * f, atlas.cornerUVs.begin() + 6 * f + 6);
    const std::vector<uint16_t> cov = tvf::rasterCoverage(one, n);
    const uint32_t h = static_cast<uint32_t>(c) * 2654435761u;
    for (size_t k = 0; k < cov.size(); ++k)
      if (cov[k]) {
        const size_t y = n - 1 - k / n, x = k % n;  // v = 0 at the bottom
        const size_t o = 4 * (y * n + x);
        rgba[o] = 64 + (h & 191), rgba[o + 1] = 64 + ((h >> 8) & 191), rgba[o + 2] = 64 + ((h >> 16) & 191);
      }
  }
  const std::vector<uint8_t> png = tvf::encodePngRgba(rgba, n, n, 8);
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), png.size());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> meshes, resolutions;
  int gutter = 2, repeat = 1;
  std::string pngDir;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--resolution" && k + 1 < argc)
      resolutions.push_back(argv[++k]);
    else if (a == "--gutter" && k + 1 < argc)
      gutter = std::atoi(argv[++k]);
    else if (a == "--png" && k + 1 < argc)
      pngDir = argv[++k];
    else if (a == "--repeat" && k + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++k]));
    else
      meshes.push_back(a);
  }
  if (meshes.empty()) {
    std::cerr
        << "usage: tvf_atlas_bench MESH... [--resolution N|auto]... [--gutter G] [--repeat N] [--png DIR]\n";
    return 2;
  }
  if (resolutions.empty()) resolutions = {"auto", "512"};
  try {
    for (const std::string& path : meshes) {
      const tvf::SurfaceMesh mesh = tvf::loadMesh(path);
      for (const std::string& rs : resolutions) {
        const int r = rs == "auto" ? pageDefaultResolution(mesh.numFaces()) : std::atoi(rs.c_str());
        std::vector<double> ms;
        tvf::TextureAtlas atlas;
        for (int i = 0; i < repeat; ++i) {
          atlas = tvf::generateAtlas(mesh, r, gutter);
          ms.push_back(atlas.milliseconds);
        }
        std::sort(ms.begin(), ms.end());
        if (!pngDir.empty()) {
          const std::string stem = path.substr(path.find_last_of('/') + 1);
          writeChartImage(atlas,
                          pngDir + "/" + stem.substr(0, stem.find('.')) + "-" + std::to_string(r) + ".png");
        }
        const tvf::AtlasMeasures& m = atlas.measures;
        std::cout << nlohmann::json{{"mesh", path},
                                    {"faces", mesh.numFaces()},
                                    {"resolution", r},
                                    {"gutter", gutter},
                                    {"charts", atlas.numCharts},
                                    {"hash", atlasHash(atlas)},
                                    {"coverage", m.coverage},
                                    {"used", atlas.used},
                                    {"seamShare", m.seamShare},
                                    {"densityP05", m.densityP05},
                                    {"densityP95", m.densityP95},
                                    {"stretchL2", m.stretchL2},
                                    {"flipped", m.flippedFaces},
                                    {"overlap", m.overlap},
                                    {"msMedian", ms[ms.size() / 2]},
                                    {"chartMs", atlas.chartMilliseconds},
                                    {"packAttempts", atlas.packAttempts},
                                    {"splits", atlas.splits},
                                    {"keptPieces", atlas.keptPieces}}
                         .dump()
                  << std::endl;
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "tvf_atlas_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
