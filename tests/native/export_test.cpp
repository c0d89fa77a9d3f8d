// Flow maps, PNG encoding and GLB export against independent truth: a flat square with known UVs and a
// constant field (exact texel values, decoded with libpng), and a stroke on a curved glTF model with its own
// UVs, exported by the CLI and read back (flow map within 2 degrees, TANGENT within 3, UVs byte-identical,
// the design restored from the GLB to 1e-9).
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "design/design_document.h"
#include "design/field_export.h"
#include "direction/representative_directions.h"
#include "field/flow_map.h"
#include "io/gltf_writer.h"
#include "io/mesh_io.h"
#include "io/png_writer.h"
#include "io/raw_field.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tvf::SurfaceMesh;

struct Image {
  int width = 0, height = 0, bits = 0;
  std::vector<uint16_t> rgba;  // 4 per pixel, row 0 first
  uint16_t at(int x, int y, int c) const { return rgba[4 * (static_cast<size_t>(y) * width + x) + c]; }
};

// libpng, not the encoder's own library, reads the files back.
Image decodePng(const std::vector<uint8_t>& bytes) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  EXPECT_TRUE(png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) << image.message;
  Image out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.bits = (image.format & PNG_FORMAT_FLAG_LINEAR) ? 16 : 8;
  // The simplified API would convert 16-bit samples to linear light with premultiplied alpha; read rows
  // with the classic API for exact samples instead.
  png_image_free(&image);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  struct Reader {
    const std::vector<uint8_t>* bytes;
    size_t offset;
  } reader{&bytes, 0};
  png_set_read_fn(png, &reader, [](png_structp p, png_bytep data, png_size_t length) {
    auto* r = static_cast<Reader*>(png_get_io_ptr(p));
    std::memcpy(data, r->bytes->data() + r->offset, length);
    r->offset += length;
  });
  png_read_info(png, info);
  out.bits = png_get_bit_depth(png, info);
  EXPECT_EQ(png_get_color_type(png, info), PNG_COLOR_TYPE_RGBA);
  const size_t rowBytes = png_get_rowbytes(png, info);
  std::vector<uint8_t> rows(rowBytes * out.height);
  std::vector<png_bytep> pointers(out.height);
  for (int y = 0; y < out.height; ++y) pointers[y] = rows.data() + y * rowBytes;
  png_read_image(png, pointers.data());
  png_destroy_read_struct(&png, &info, nullptr);
  out.rgba.resize(static_cast<size_t>(out.width) * out.height * 4);
  for (size_t i = 0; i < out.rgba.size(); ++i)
    out.rgba[i] = out.bits == 16 ? static_cast<uint16_t>(rows[2 * i] << 8 | rows[2 * i + 1]) : rows[i];
  return out;
}

std::vector<uint8_t> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// An affine, non-conformal UV map of the unit square into [0,1]^2 (sheared and scaled, not filling it).
Eigen::Vector2d squareUV(double x, double y) {
  return {0.1 + 0.6 * x + 0.2 * y, 0.15 + 0.5 * y};
}

std::vector<float> cornerUVsOf(const SurfaceMesh& m, Eigen::Vector2d (*uv)(double, double)) {
  std::vector<float> uvs;
  for (int32_t v : m.triangles) {
    const Eigen::Vector2d q = uv(m.positions[3 * v], m.positions[3 * v + 1]);
    uvs.push_back(static_cast<float>(q.x()));
    uvs.push_back(static_cast<float>(q.y()));
  }
  return uvs;
}

std::vector<double> constantOneForm(const SurfaceMesh& m, const tvf::MeshTopology& t,
                                    const Eigen::Vector3d& u) {
  std::vector<double> c(t.numEdges);
  for (int e = 0; e < t.numEdges; ++e) c[e] = u.dot(tvf::edgeVector(m, t, e));
  return c;
}

TEST(FlowMap, FlatSquareWithAConstantFieldGivesExactTexels) {
  const SurfaceMesh m = tvf::testing::flatGrid(6);
  const tvf::MeshTopology t = tvf::buildTopology(m);
  const std::vector<float> uvs = cornerUVsOf(m, squareUV);
  const Eigen::Vector3d u(0.8, -0.35, 0);
  const std::vector<double> c = constantOneForm(m, t, u);
  // The field pushed into UV by the affine map's linear part: (du, dv) = A u, normalized.
  Eigen::Matrix2d A;
  A << 0.6, 0.2, 0, 0.5;
  const Eigen::Vector2d d = (A * u.head<2>()).normalized();
  const int n = 64;
  for (int bits : {8, 16}) {
    for (auto convention : {tvf::FlowMapConvention::Gltf, tvf::FlowMapConvention::OpenGl}) {
      tvf::FieldExportOptions options;
      options.size = n;
      options.bits = bits;
      options.convention = convention;
      options.gutterTexels = 3;
      const Image image = decodePng(tvf::exportFlowMapPng(m, t, uvs, c, options));
      ASSERT_EQ(image.width, n);
      ASSERT_EQ(image.bits, bits);
      const double top = bits == 8 ? 255 : 65535;
      const double sign = convention == tvf::FlowMapConvention::Gltf ? 1 : -1;
      int inside = 0, outside = 0;
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          // Texel centre back to the square through the inverse map; row y is v = (y + 0.5) / n.
          const Eigen::Vector2d q((x + 0.5) / n, (y + 0.5) / n);
          const Eigen::Vector2d p = A.inverse() * (q - Eigen::Vector2d(0.1, 0.15));
          const bool covered = p.x() >= 0 && p.x() <= 1 && p.y() >= 0 && p.y() <= 1;
          // Texels more than the gutter away from the chart are empty.
          const double away = std::max({-p.x(), p.x() - 1, -p.y(), p.y() - 1}) * 0.5 * n;
          if (covered) {
            ++inside;
            EXPECT_EQ(image.at(x, y, 0), std::lround(top * (0.5 + 0.5 * d.x()))) << x << "," << y;
            EXPECT_EQ(image.at(x, y, 1), std::lround(top * (0.5 + sign * 0.5 * d.y()))) << x << "," << y;
            EXPECT_EQ(image.at(x, y, 2), top);
            EXPECT_EQ(image.at(x, y, 3), top);
          } else if (away > 8) {
            ++outside;
            EXPECT_EQ(image.at(x, y, 3), 0);
            EXPECT_EQ(image.at(x, y, 0), std::lround(top * 0.5));
          }
        }
      }
      EXPECT_GT(inside, 800);
      EXPECT_GT(outside, 200);
    }
  }
}

TEST(FlowMap, GutterCoversTexelsNextToChartsOnly) {
  const SurfaceMesh m = tvf::testing::flatGrid(4);
  const tvf::MeshTopology t = tvf::buildTopology(m);
  const std::vector<float> uvs = cornerUVsOf(m, squareUV);
  const std::vector<double> c = constantOneForm(m, t, {1, 0, 0});
  for (int gutter : {0, 2, 4}) {
    const tvf::FlowField f = tvf::rasterizeFlowField(m, t, uvs.data(), c.data(), 32, gutter);
    int filled = 0;
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        if (f.coverage[y * 32 + x] != 2) continue;
        ++filled;
        // Chebyshev distance to the nearest inside texel is at most the gutter.
        int nearest = 99;
        for (int yy = 0; yy < 32; ++yy)
          for (int xx = 0; xx < 32; ++xx)
            if (f.coverage[yy * 32 + xx] == 1)
              nearest = std::min(nearest, std::max(std::abs(xx - x), std::abs(yy - y)));
        EXPECT_LE(nearest, gutter);
      }
    if (gutter == 0) EXPECT_EQ(filled, 0);
    if (gutter > 0) EXPECT_GT(filled, 10 * gutter);
  }
}

TEST(Png, SixteenBitSamplesSurviveLibpng) {
  const int w = 7, h = 5;
  std::vector<uint16_t> samples(w * h * 4);
  for (size_t i = 0; i < samples.size(); ++i) samples[i] = static_cast<uint16_t>((i * 40503u) & 0xFFFF);
  const Image image = decodePng(tvf::encodePngRgba(samples, w, h, 16));
  EXPECT_EQ(image.bits, 16);
  EXPECT_EQ(image.width, w);
  EXPECT_EQ(image.height, h);
  EXPECT_EQ(image.rgba, samples);
  EXPECT_THROW(tvf::encodePngRgba(samples, w, h, 12), tvf::InputError);
}

// ---- A curved glTF model with its own UVs, exported through the CLI ------------------------------------

constexpr int kGrid = 24;

double height(double x, double y) {
  return 0.25 * std::sin(2.5 * x) * std::cos(2.0 * y);
}

Eigen::Vector2d warpedUV(double x, double y) {
  return {0.05 + 0.8 * x + 0.1 * y * y, 0.05 + 0.7 * y + 0.1 * x};
}

struct Glb {
  json doc;
  std::vector<uint8_t> bin;
};

Glb parseGlb(const std::vector<uint8_t>& bytes) {
  const auto u32 = [&](size_t o) {
    return uint32_t{bytes[o]} | uint32_t{bytes[o + 1]} << 8 | uint32_t{bytes[o + 2]} << 16 |
           uint32_t{bytes[o + 3]} << 24;
  };
  Glb glb;
  const uint32_t jsonLength = u32(12);
  glb.doc = json::parse(bytes.begin() + 20, bytes.begin() + 20 + jsonLength);
  if (bytes.size() > 28 + jsonLength) {
    const uint32_t binLength = u32(20 + jsonLength);
    glb.bin.assign(bytes.begin() + 28 + jsonLength, bytes.begin() + 28 + jsonLength + binLength);
  }
  return glb;
}

std::vector<float> accessorFloats(const Glb& glb, int index) {
  const json& a = glb.doc["accessors"][index];
  const json& view = glb.doc["bufferViews"][a["bufferView"].get<int>()];
  const int components = a["type"] == "VEC2" ? 2 : a["type"] == "VEC3" ? 3 : 4;
  std::vector<float> out(a["count"].get<size_t>() * components);
  std::memcpy(out.data(), glb.bin.data() + view.value("byteOffset", 0) + a.value("byteOffset", 0),
              out.size() * 4);
  return out;
}

// A height-field patch as a GLB: positions in the node's local frame (scaled by 2, translated), own UVs, a
// material with a base colour, split vertices along no seam (one primitive, indexed). moreAttributes adds a
// TEXCOORD_1 (the UVs halved), a COLOR_0 of three normalized bytes (elements shorter than 4 bytes) and a
// morph target moving each vertex up by x / 10.
std::vector<uint8_t> curvedPatchGlb(bool normalMapped = false, bool moreAttributes = false) {
  std::vector<float> positions, uvs;
  std::vector<uint32_t> indices;
  for (int j = 0; j <= kGrid; ++j)
    for (int i = 0; i <= kGrid; ++i) {
      const double x = double(i) / kGrid, y = double(j) / kGrid;
      positions.insert(positions.end(), {float(x), float(y), float(height(x, y))});
      const Eigen::Vector2d q = warpedUV(x, y);
      uvs.insert(uvs.end(), {float(q.x()), float(q.y())});
    }
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const uint32_t a = j * (kGrid + 1) + i, b = a + 1, c = a + kGrid + 2, d = a + kGrid + 1;
      indices.insert(indices.end(), {a, b, c, a, c, d});
    }
  std::vector<uint8_t> bin;
  const auto put = [&](const void* data, size_t size) {
    const size_t offset = bin.size();
    bin.insert(bin.end(), static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + size);
    return offset;
  };
  const size_t p = put(positions.data(), positions.size() * 4), t = put(uvs.data(), uvs.size() * 4),
               x = put(indices.data(), indices.size() * 4);
  float lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (size_t k = 0; k < positions.size(); ++k) {
    lo[k % 3] = std::min(lo[k % 3], positions[k]);
    hi[k % 3] = std::max(hi[k % 3], positions[k]);
  }
  const size_t vertices = positions.size() / 3;
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"translation", {1, 2, 3}}, {"scale", {2, 2, 2}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
      {"materials", {{{"name", "own"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.5, 0.2, 1}}}}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", vertices},
         {"type", "VEC3"},
         {"min", lo},
         {"max", hi}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", p}, {"byteLength", positions.size() * 4}, {"target", 34962}},
        {{"buffer", 0}, {"byteOffset", t}, {"byteLength", uvs.size() * 4}, {"target", 34962}},
        {{"buffer", 0}, {"byteOffset", x}, {"byteLength", indices.size() * 4}, {"target", 34963}}}},
      {"buffers", {{{"byteLength", bin.size()}}}}};
  if (moreAttributes) {
    std::vector<float> uv1, up;
    std::vector<uint8_t> colours;
    for (size_t v = 0; v < vertices; ++v) {
      uv1.insert(uv1.end(), {0.5f * uvs[2 * v], 0.5f * uvs[2 * v + 1]});
      up.insert(up.end(), {0.0f, 0.0f, 0.1f * positions[3 * v]});
      colours.insert(colours.end(), {uint8_t(v % 251), uint8_t(v % 13), uint8_t(v % 7)});
    }
    const auto view = [&](const void* data, size_t size) {
      bin.resize((bin.size() + 3) / 4 * 4, 0);
      doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", put(data, size)}, {"byteLength", size}});
      return doc["bufferViews"].size() - 1;
    };
    const auto accessor = [&](size_t view, int type, const char* shape) {
      doc["accessors"].push_back(
          {{"bufferView", view}, {"componentType", type}, {"count", vertices}, {"type", shape}});
      return doc["accessors"].size() - 1;
    };
    json& primitive = doc["meshes"][0]["primitives"][0];
    primitive["attributes"]["TEXCOORD_1"] = accessor(view(uv1.data(), uv1.size() * 4), 5126, "VEC2");
    primitive["attributes"]["COLOR_0"] = accessor(view(colours.data(), colours.size()), 5121, "VEC3");
    doc["accessors"].back()["normalized"] = true;
    primitive["targets"] = {{{"POSITION", accessor(view(up.data(), up.size() * 4), 5126, "VEC3")}}};
    doc["accessors"].back()["min"] = {0.0, 0.0, 0.0};
    doc["accessors"].back()["max"] = {0.0, 0.0, 0.1};
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    doc["buffers"][0]["byteLength"] = bin.size();
  }
  if (normalMapped) {
    // A flat 1x1 normal map: enough to make the material normal-mapped.
    const std::vector<uint8_t> png = tvf::encodePngRgba({128, 128, 255, 255}, 1, 1, 8);
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    const size_t offset = put(png.data(), png.size());
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", png.size()}});
    doc["images"] = {{{"bufferView", 3}, {"mimeType", "image/png"}}};
    doc["textures"] = {{{"source", 0}}};
    doc["materials"][0]["normalTexture"] = {{"index", 0}};
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    doc["buffers"][0]["byteLength"] = bin.size();
  }
  std::string text = doc.dump();
  text.resize((text.size() + 3) / 4 * 4, ' ');
  std::vector<uint8_t> out;
  const auto u32 = [&](uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k)));
  };
  u32(0x46546C67u);
  u32(2);
  u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  u32(uint32_t(text.size()));
  u32(0x4E4F534Au);
  out.insert(out.end(), text.begin(), text.end());
  u32(uint32_t(bin.size()));
  u32(0x004E4942u);
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

// The world-space surface point above (x, y) of the patch (the node scales by 2 and translates).
tvf::SurfacePoint pointAbove(const SurfaceMesh& m, double x, double y) {
  const Eigen::Vector2d target(1 + 2 * x, 2 + 2 * y);
  for (int f = 0; f < m.numFaces(); ++f) {
    Eigen::Vector3d p[3];
    tvf::facePositions(m, f, p);
    const Eigen::Vector2d a = p[0].head<2>(), b = p[1].head<2>(), c = p[2].head<2>();
    const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
      return u.x() * v.y() - u.y() * v.x();
    };
    const double area = cross(b - a, c - a);
    const double w[3] = {cross(b - target, c - target) / area, cross(c - target, a - target) / area,
                         cross(a - target, b - target) / area};
    if (w[0] >= -1e-12 && w[1] >= -1e-12 && w[2] >= -1e-12) return {f, {w[0], w[1], w[2]}};
  }
  ADD_FAILURE() << "no face above " << x << "," << y;
  return {0, {1, 0, 0}};
}

Eigen::Vector3d positionAt(const SurfaceMesh& m, const tvf::SurfacePoint& s) {
  Eigen::Vector3d p[3];
  tvf::facePositions(m, s.face, p);
  return s.bary[0] * p[0] + s.bary[1] * p[1] + s.bary[2] * p[2];
}

Eigen::Vector2d uvAt(const std::vector<float>& uvs, const tvf::SurfacePoint& s) {
  Eigen::Vector2d q(0, 0);
  for (int k = 0; k < 3; ++k)
    q += s.bary[k] * Eigen::Vector2d(uvs[6 * s.face + 2 * k], uvs[6 * s.face + 2 * k + 1]);
  return q;
}

// A tangent vector of face f taken to UV by the face's linear map.
Eigen::Vector2d toUV(const SurfaceMesh& m, const std::vector<float>& uvs, int f, const Eigen::Vector3d& t) {
  Eigen::Vector3d p[3];
  tvf::facePositions(m, f, p);
  Eigen::Matrix<double, 3, 2> E;
  E << p[1] - p[0], p[2] - p[0];
  const Eigen::Vector2d ab = E.colPivHouseholderQr().solve(t);
  const Eigen::Vector2d q0(uvs[6 * f], uvs[6 * f + 1]), q1(uvs[6 * f + 2], uvs[6 * f + 3]),
      q2(uvs[6 * f + 4], uvs[6 * f + 5]);
  return ab.x() * (q1 - q0) + ab.y() * (q2 - q0);
}

double degreesBetween(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / M_PI;
}

int runCli(const std::string& args) {
  const std::string command = std::string(TVF_CLI_PATH) + " export " + args + " 2>/dev/null";
  return WEXITSTATUS(std::system(command.c_str()));
}

class CurvedPatchExport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tvf_export_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    source_ = curvedPatchGlb();
    std::ofstream(dir_ / "patch.glb", std::ios::binary)
        .write(reinterpret_cast<const char*>(source_.data()), source_.size());
    mesh_ = tvf::loadMesh((dir_ / "patch.glb").string());
    // A diagonal stroke, densely sampled the way the page picks points.
    for (int s = 0; s <= 40; ++s) {
      const double a = 0.15 + 0.7 * s / 40.0;
      stroke_.push_back(pointAbove(mesh_, a, 0.3 + 0.4 * a));
    }
    json points = json::array();
    for (const auto& p : stroke_)
      points.push_back({{"face", p.face}, {"bary", {p.bary[0], p.bary[1], p.bary[2]}}});
    design_ = {{"boundary", "free"},
               {"constraints", {{{"type", "stroke"}, {"points", points}, {"strength", 1}, {"weight", 100}}}}};
    std::ofstream(dir_ / "design.json") << design_.dump();
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Unit stroke direction between samples k and k+1, at their midpoint's face.
  Eigen::Vector3d strokeTangent(size_t k) const {
    return (positionAt(mesh_, stroke_[k + 1]) - positionAt(mesh_, stroke_[k])).normalized();
  }

  // The curved patch with a normal map exported with `design`: the worst angle between the stroke and the
  // direction decoded from anisotropyTexture at the stroke's texels (in the face's orthonormal UV frame),
  // modulo pi for a line field.
  double anisotropyTextureDeviation(const std::string& design, const std::string& outName, bool moduloPi) {
    const std::vector<uint8_t> source = curvedPatchGlb(true);
    std::ofstream(dir_ / "mapped.glb", std::ios::binary)
        .write(reinterpret_cast<const char*>(source.data()), static_cast<std::streamsize>(source.size()));
    EXPECT_EQ(runCli(path("mapped.glb") + " " + path(design) + " --glb " + path(outName) + " --size 256"), 0);
    const Glb out = parseGlb(readBytes(dir_ / outName));
    const json& primitive = out.doc["meshes"][0]["primitives"][0];
    EXPECT_FALSE(primitive["attributes"].contains("TANGENT"));  // the normal map's frame stays the viewer's
    const json& anisotropy = out.doc["materials"][0]["extensions"]["KHR_materials_anisotropy"];
    EXPECT_TRUE(anisotropy.contains("anisotropyTexture"));
    if (!anisotropy.contains("anisotropyTexture")) return 180;
    const json& image =
        out.doc["images"][out.doc["textures"][anisotropy["anisotropyTexture"]["index"].get<int>()]["source"]
                              .get<int>()];
    const json& view = out.doc["bufferViews"][image["bufferView"].get<int>()];
    const auto begin = out.bin.begin() + view["byteOffset"].get<long>();
    const Image map = decodePng(std::vector<uint8_t>(begin, begin + view["byteLength"].get<long>()));
    // Expected: the stroke direction in the face's orthonormal UV frame (T along dp/du, B = N x T), the frame
    // KHR_materials_anisotropy measures directions in when tangents follow the UVs (MikkTSpace).
    double worst = 0;
    for (size_t k = 0; k + 1 < stroke_.size(); ++k) {
      const int f = stroke_[k].face;
      Eigen::Vector3d p[3];
      tvf::facePositions(mesh_, f, p);
      const Eigen::Vector3d n = tvf::faceNormal(mesh_, f);
      // dp/du: the 3D vector whose UV image is (1, 0).
      Eigen::Matrix2d D;
      const float* uv = &mesh_.cornerUVs[6 * f];
      D << uv[2] - uv[0], uv[4] - uv[0], uv[3] - uv[1], uv[5] - uv[1];
      const Eigen::Vector2d ab = D.inverse() * Eigen::Vector2d(1, 0);
      const Eigen::Vector3d T = (ab.x() * (p[1] - p[0]) + ab.y() * (p[2] - p[0])).normalized(),
                            B = n.cross(T);
      const Eigen::Vector3d along = strokeTangent(k);
      const Eigen::Vector2d q = uvAt(mesh_.cornerUVs, stroke_[k]);
      const int x = int(q.x() * 256), y = int(q.y() * 256);
      const Eigen::Vector2d decoded(map.at(x, y, 0) / 127.5 - 1, map.at(x, y, 1) / 127.5 - 1);
      const double d = degreesBetween(decoded, Eigen::Vector2d(along.dot(T), along.dot(B)));
      worst = std::max(worst, moduloPi ? std::min(d, 180 - d) : d);
    }
    return worst;
  }

  fs::path dir_;
  std::vector<uint8_t> source_;
  SurfaceMesh mesh_;
  std::vector<tvf::SurfacePoint> stroke_;
  json design_;
};

TEST_F(CurvedPatchExport, FlowMapPointsAlongTheStrokeInBothConventions) {
  const int n = 256;
  for (const std::string convention : {"gltf", "opengl"}) {
    ASSERT_EQ(runCli(path("patch.glb") + " " + path("design.json") + " --flowmap " + path("flow.png") +
                     " --size 256 --convention " + convention),
              0)
        << "";
    const Image image = decodePng(readBytes(dir_ / "flow.png"));
    double worst = 0;
    for (size_t k = 0; k + 1 < stroke_.size(); ++k) {
      const tvf::SurfacePoint& s = stroke_[k];
      const Eigen::Vector2d expected = toUV(mesh_, mesh_.cornerUVs, s.face, strokeTangent(k));
      const Eigen::Vector2d q = uvAt(mesh_.cornerUVs, s);
      const int x = int(q.x() * n), y = int(q.y() * n);  // row y holds v = (y + 0.5) / n in both conventions
      ASSERT_EQ(image.at(x, y, 3), 255);
      const double du = image.at(x, y, 0) / 127.5 - 1, g = image.at(x, y, 1) / 127.5 - 1;
      const Eigen::Vector2d decoded(du, convention == "gltf" ? g : -g);
      worst = std::max(worst, degreesBetween(decoded, expected));
    }
    EXPECT_LT(worst, 2.0) << convention;
    std::cout << "[ measured ] flow map (" << convention << ") worst deviation from the stroke: " << worst
              << " deg\n";
  }
}

TEST_F(CurvedPatchExport, GlbKeepsTheModelAndCarriesTheField) {
  ASSERT_EQ(
      runCli(path("patch.glb") + " " + path("design.json") + " --glb " + path("out.glb") + " --size 128"), 0);
  const std::vector<uint8_t> bytes = readBytes(dir_ / "out.glb");
  const Glb in = parseGlb(source_), out = parseGlb(bytes);
  const json& primitive = out.doc["meshes"][0]["primitives"][0];
  // The model's own UVs and positions: same accessors, same floats.
  EXPECT_EQ(primitive["attributes"]["TEXCOORD_0"], 1);
  EXPECT_EQ(accessorFloats(out, 1), accessorFloats(in, 1));
  EXPECT_EQ(accessorFloats(out, 0), accessorFloats(in, 0));
  EXPECT_EQ(out.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"],
            in.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"]);
  const json& anisotropy = out.doc["materials"][0]["extensions"]["KHR_materials_anisotropy"];
  EXPECT_EQ(anisotropy["anisotropyStrength"], 1.0);
  EXPECT_TRUE(std::find(out.doc["extensionsUsed"].begin(), out.doc["extensionsUsed"].end(),
                        "KHR_materials_anisotropy") != out.doc["extensionsUsed"].end());
  // TANGENT (local frame) taken to world by the node's scale: within 3 degrees of the stroke at the
  // vertices of the faces it crosses.
  const std::vector<float> tangents = accessorFloats(out, primitive["attributes"]["TANGENT"].get<int>());
  const std::vector<float> field = accessorFloats(out, primitive["attributes"]["_FIELD"].get<int>());
  ASSERT_EQ(tangents.size(), 4 * mesh_.sourceToWelded.size());
  double worst = 0;
  int checked = 0;
  for (size_t k = 0; k + 1 < stroke_.size(); ++k) {
    const Eigen::Vector3d along = strokeTangent(k);
    for (int c = 0; c < 3; ++c) {
      const int32_t v = mesh_.triangles[3 * stroke_[k].face + c];  // welded = source here (no seams)
      const Eigen::Vector3d t(tangents[4 * v], tangents[4 * v + 1], tangents[4 * v + 2]);
      EXPECT_NEAR(t.norm(), 1.0, 1e-6);
      EXPECT_EQ(tangents[4 * v + 3], 1.0f);
      const Eigen::Vector3d n = tvf::faceNormal(mesh_, stroke_[k].face);
      worst = std::max(worst, degreesBetween(t - n.dot(t) * n, along - n.dot(along) * n));
      EXPECT_GT(Eigen::Vector3d(field[3 * v], field[3 * v + 1], field[3 * v + 2]).dot(t), 0);
      ++checked;
    }
  }
  EXPECT_GT(checked, 60);
  EXPECT_LT(worst, 3.0);
  std::cout << "[ measured ] TANGENT worst deviation from the stroke: " << worst << " deg over " << checked
            << " corners\n";
  // The flow map is in the file and named in extras.
  const json& extras = out.doc["extras"][tvf::kGlbExtrasKey];
  EXPECT_TRUE(extras.contains("flowMapTexture"));
  EXPECT_EQ(extras["design"]["constraints"].size(), 1u);
}

TEST_F(CurvedPatchExport, ReopeningTheGlbRestoresTheDesign) {
  ASSERT_EQ(
      runCli(path("patch.glb") + " " + path("design.json") + " --glb " + path("out.glb") + " --size 64"), 0);
  tvf::Designer original(tvf::loadMesh(path("patch.glb")));
  tvf::applyDesignDocument(original, design_);
  original.solve();
  const std::vector<uint8_t> bytes = readBytes(dir_ / "out.glb");
  tvf::Designer reopened(tvf::loadMeshFromMemory(bytes.data(), bytes.size(), tvf::MeshFormat::Glb));
  tvf::applyDesignDocument(reopened, tvf::readEmbeddedDesign(bytes.data(), bytes.size()));
  reopened.solve();
  ASSERT_EQ(reopened.oneForm().size(), original.oneForm().size());
  double worst = 0;
  for (size_t e = 0; e < original.oneForm().size(); ++e)
    worst = std::max(worst, std::abs(reopened.oneForm()[e] - original.oneForm()[e]));
  EXPECT_LT(worst, 1e-9);
  // A GLB given as the design argument replays its embedded design.
  EXPECT_EQ(
      runCli(path("out.glb") + " " + path("out.glb") + " --flowmap " + path("again.png") + " --size 32"), 0);
}

TEST_F(CurvedPatchExport, BadRequestsAreRefusedWithAReason) {
  EXPECT_EQ(runCli(path("patch.glb") + " " + path("design.json")), 2);
  EXPECT_EQ(
      runCli(path("patch.glb") + " " + path("design.json") + " --flowmap " + path("f.png") + " --bits 12"),
      2);
  EXPECT_EQ(runCli(path("patch.glb") + " " + path("design.json") + " --flowmap " + path("f.png") +
                   " --convention dx"),
            2);
  // A design that does not fit the model is refused.
  std::ofstream(dir_ / "tri.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(runCli(path("tri.off") + " " + path("design.json") + " --glb " + path("tri.glb")), 2);
}

// Without UVs the exports use the core's generated atlas, and the GLB carries it as TEXCOORD_0: the flow map
// read through those UVs still follows the stroke.
TEST_F(CurvedPatchExport, AModelWithoutUVsGetsAGeneratedAtlas) {
  {
    std::ofstream off(dir_ / "patch.off");
    off.precision(17);
    off << "OFF\n" << mesh_.numVertices() << " " << mesh_.numFaces() << " 0\n";
    for (int v = 0; v < mesh_.numVertices(); ++v)
      off << mesh_.positions[3 * v] << " " << mesh_.positions[3 * v + 1] << " " << mesh_.positions[3 * v + 2]
          << "\n";
    for (int f = 0; f < mesh_.numFaces(); ++f)
      off << "3 " << mesh_.triangles[3 * f] << " " << mesh_.triangles[3 * f + 1] << " "
          << mesh_.triangles[3 * f + 2] << "\n";
  }
  ASSERT_EQ(runCli(path("patch.off") + " " + path("design.json") + " --glb " + path("g.glb") + " --flowmap " +
                   path("g.png") + " --size 256"),
            0);
  const Glb glb = parseGlb(readBytes(dir_ / "g.glb"));
  const json& primitive = glb.doc["meshes"][0]["primitives"][0];
  const std::vector<float> texcoords = accessorFloats(glb, primitive["attributes"]["TEXCOORD_0"].get<int>());
  const json& ia = glb.doc["accessors"][primitive["indices"].get<int>()];
  std::vector<uint32_t> indices(ia["count"].get<size_t>());
  std::memcpy(
      indices.data(),
      glb.bin.data() + glb.doc["bufferViews"][ia["bufferView"].get<int>()]["byteOffset"].get<size_t>(),
      indices.size() * 4);
  ASSERT_EQ(indices.size(), mesh_.triangles.size());
  std::vector<float> uvs;
  for (uint32_t i : indices) uvs.insert(uvs.end(), {texcoords[2 * i], texcoords[2 * i + 1]});
  const Image image = decodePng(readBytes(dir_ / "g.png"));
  double worst = 0;
  for (size_t k = 0; k + 1 < stroke_.size(); ++k) {
    const Eigen::Vector2d expected = toUV(mesh_, uvs, stroke_[k].face, strokeTangent(k));
    const Eigen::Vector2d q = uvAt(uvs, stroke_[k]);
    const int x = int(q.x() * 256), y = int(q.y() * 256);
    ASSERT_EQ(image.at(x, y, 3), 255);
    const Eigen::Vector2d decoded(image.at(x, y, 0) / 127.5 - 1, image.at(x, y, 1) / 127.5 - 1);
    worst = std::max(worst, degreesBetween(decoded, expected));
  }
  EXPECT_LT(worst, 2.0);
  std::cout << "[ measured ] generated atlas: flow map worst deviation from the stroke: " << worst
            << " deg\n";
  // Without the flow map the GLB keeps the model's layout: no atlas, no TEXCOORD_0.
  ASSERT_EQ(runCli(path("patch.glb") + " " + path("design.json") + " --glb " + path("plain.glb") +
                   " --no-embed-flowmap"),
            0);
  EXPECT_FALSE(
      parseGlb(readBytes(dir_ / "plain.glb")).doc["extras"][tvf::kGlbExtrasKey].contains("flowMapTexture"));
}

// export --stripes bakes the field's stripe pattern into the GLB's base colour over the model's own UVs:
// along the stroke the colour hardly changes, across it it goes through whole stripes (the grey's variance
// over a segment of about one period, in both directions, at every stroke sample). --stripes without --glb,
// or with no frequency, is refused by name. --stripe-width sets the dark share of the baked texels.
TEST_F(CurvedPatchExport, StripesAreBakedIntoTheBaseColourAlongTheStroke) {
  const int n = 512;
  ASSERT_EQ(runCli(path("patch.glb") + " " + path("design.json") + " --glb " + path("s.glb") +
                   " --stripes 6 --size 512"),
            0);
  const auto baseColour = [&](const std::string& name) {
    const Glb glb = parseGlb(readBytes(dir_ / name));
    const json& pbr = glb.doc["materials"][0]["pbrMetallicRoughness"];
    EXPECT_TRUE(pbr.contains("baseColorTexture"));
    const json& image =
        glb.doc["images"]
               [glb.doc["textures"][pbr["baseColorTexture"]["index"].get<int>()]["source"].get<int>()];
    const json& view = glb.doc["bufferViews"][image["bufferView"].get<int>()];
    const auto begin = glb.bin.begin() + view.value("byteOffset", 0);
    return decodePng(std::vector<uint8_t>(begin, begin + view["byteLength"].get<long>()));
  };
  const Image map = baseColour("s.glb");
  ASSERT_EQ(map.width, n);
  // The grey's variance along the stroke and across it, summed over the stroke's samples.
  const auto variances = [&](const Image& image) {
    const auto variance = [&](const Eigen::Vector2d& q, const Eigen::Vector2d& d) {
      double sum = 0, sum2 = 0;
      for (int s = -16; s <= 16; ++s) {
        const Eigen::Vector2d p = q + s * d;
        const int x = std::clamp(int(p.x()), 0, n - 1), y = std::clamp(int(p.y()), 0, n - 1);
        sum += image.at(x, y, 0), sum2 += double(image.at(x, y, 0)) * image.at(x, y, 0);
      }
      return sum2 / 33 - (sum / 33) * (sum / 33);
    };
    std::pair<double, double> out{0, 0};
    for (size_t k = 5; k + 6 < stroke_.size(); ++k) {
      const Eigen::Vector2d t = toUV(mesh_, mesh_.cornerUVs, stroke_[k].face, strokeTangent(k)).normalized();
      const Eigen::Vector2d q = uvAt(mesh_.cornerUVs, stroke_[k]) * n;
      out.first += variance(q, t);
      out.second += variance(q, Eigen::Vector2d(-t.y(), t.x()));
    }
    return out;
  };
  const auto [along, across] = variances(map);
  std::cout << "[ measured ] stripes: grey variance along the stroke " << along << ", across " << across
            << "\n";
  EXPECT_GT(across, 1000.0 * (stroke_.size() - 11));  // whole stripes: a light-dark contrast of ~180 levels
  EXPECT_LT(along, 0.05 * across);
  // --stripes-across: the other way round.
  ASSERT_EQ(runCli(path("patch.glb") + " " + path("design.json") + " --glb " + path("a.glb") +
                   " --stripes 6 --size 512 --stripes-across"),
            0);
  const auto [turnedAlong, turnedAcross] = variances(baseColour("a.glb"));
  std::cout << "[ measured ] stripes across: grey variance along the stroke " << turnedAlong << ", across "
            << turnedAcross << "\n";
  EXPECT_GT(turnedAlong, 1000.0 * (stroke_.size() - 11));
  // (The lines across a curved stroke fan out and bend a little, so along them the grey varies more: 0.045
  // here.)
  EXPECT_LT(turnedAcross, 0.1 * turnedAlong);
  EXPECT_EQ(
      runCli(path("patch.glb") + " " + path("design.json") + " --flowmap " + path("f.png") + " --stripes 6"),
      2);
  EXPECT_EQ(
      runCli(path("patch.glb") + " " + path("design.json") + " --glb " + path("z.glb") + " --stripes 0"), 2);
  // The dark share of the texels the faces cover (grey under the middle of light and dark): 1/2 at the
  // profile's own width, 0.2 asked.
  ASSERT_EQ(runCli(path("patch.glb") + " " + path("design.json") + " --glb " + path("w.glb") +
                   " --stripes 6 --size 512 --stripe-width 0.2"),
            0);
  const auto darkShare = [&](const Image& image) {
    double dark = 0, covered = 0;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        if (image.at(x, y, 3) < 255) continue;
        ++covered;
        dark += image.at(x, y, 0) < (236 + 52) / 2;
      }
    return dark / std::max(covered, 1.0);
  };
  const double own = darkShare(map), narrow = darkShare(baseColour("w.glb"));
  std::cout << "[ measured ] stripes: dark share " << own << " at the profile's width, " << narrow
            << " at 0.2\n";
  EXPECT_NEAR(own, 0.5, 0.05);
  EXPECT_NEAR(narrow, 0.2, 0.05);
  // A design with nothing to shape its field: no direction for stripes, refused (the page shows none).
  std::ofstream(dir_ / "empty.json") << json{{"boundary", "free"}, {"constraints", json::array()}}.dump();
  EXPECT_EQ(runCli(path("patch.glb") + " " + path("empty.json") + " --glb " + path("e.glb") + " --stripes 6"),
            2);
  EXPECT_EQ(runCli(path("patch.glb") + " " + path("empty.json") + " --glb " + path("e.glb")), 0);
  for (const char* bad : {" --stripes 6 --stripe-width 1.5", " --stripe-width 0.2", " --stripes-across"})
    EXPECT_EQ(runCli(path("patch.glb") + " " + path("design.json") + " --glb " + path("z.glb") + bad), 2)
        << bad;
}

// Element i of an accessor as bytes (its bufferView's stride honoured).
std::vector<uint8_t> elementBytes(const Glb& glb, int index, size_t i) {
  const json& a = glb.doc["accessors"][index];
  const json& view = glb.doc["bufferViews"][a["bufferView"].get<int>()];
  const size_t components = a["type"] == "SCALAR" ? 1 : a["type"] == "VEC2" ? 2 : a["type"] == "VEC3" ? 3 : 4;
  const int type = a["componentType"].get<int>();
  const size_t size = components * (type == 5121 || type == 5120 ? 1 : type == 5123 || type == 5122 ? 2 : 4);
  const size_t stride = view.value("byteStride", size);
  const auto begin = glb.bin.begin() + view.value("byteOffset", 0) + a.value("byteOffset", 0) + i * stride;
  return std::vector<uint8_t>(begin, begin + size);
}

std::vector<uint32_t> indicesOf(const Glb& glb, const json& primitive) {
  const int index = primitive["indices"].get<int>();
  std::vector<uint32_t> out;
  for (size_t i = 0; i < glb.doc["accessors"][index]["count"].get<size_t>(); ++i) {
    const std::vector<uint8_t> b = elementBytes(glb, index, i);
    uint32_t v = 0;
    for (size_t k = 0; k < b.size(); ++k) v |= uint32_t(b[k]) << (8 * k);
    out.push_back(v);
  }
  return out;
}

// A glTF whose own layout is kept (its UVs are an atlas) gets the stripe phase too, in its first free texture
// coordinate set (TEXCOORD_1 holds something of its own here), its vertices split where the phase jumps
// (round the branch points a vortex's stripes have). Every corner keeps each of its attributes and its morph
// target's value; its phase is the one the same welded mesh's GLB built anew carries (an OFF of it); and the
// file opens as the same welded mesh, so its embedded design still fits.
TEST_F(CurvedPatchExport, AKeptLayoutCarriesThePhaseSplitWhereItJumps) {
  const std::vector<uint8_t> rich = curvedPatchGlb(false, true);
  std::ofstream(dir_ / "rich.glb", std::ios::binary)
      .write(reinterpret_cast<const char*>(rich.data()), static_cast<std::streamsize>(rich.size()));
  const int centre = pointAbove(mesh_, 0.5, 0.5).face;
  std::ofstream(dir_ / "vortex.json")
      << json{{"constraints", {{{"type", "vortex"}, {"face", centre}, {"strength", 1}}}}}.dump();
  {
    std::ofstream off(dir_ / "welded.off");
    off.precision(17);
    off << "OFF\n" << mesh_.numVertices() << " " << mesh_.numFaces() << " 0\n";
    for (int32_t v = 0; v < mesh_.numVertices(); ++v)
      off << mesh_.positions[3 * v] << " " << mesh_.positions[3 * v + 1] << " " << mesh_.positions[3 * v + 2]
          << "\n";
    for (int32_t f = 0; f < mesh_.numFaces(); ++f)
      off << "3 " << mesh_.triangles[3 * f] << " " << mesh_.triangles[3 * f + 1] << " "
          << mesh_.triangles[3 * f + 2] << "\n";
  }
  ASSERT_EQ(runCli(path("rich.glb") + " " + path("vortex.json") + " --glb " + path("kept.glb") +
                   " --stripes 6 --size 128"),
            0);
  ASSERT_EQ(runCli(path("welded.off") + " " + path("vortex.json") + " --glb " + path("anew.glb") +
                   " --stripes 6 --size 128"),
            0);
  const Glb source = parseGlb(rich), kept = parseGlb(readBytes(dir_ / "kept.glb")),
            anew = parseGlb(readBytes(dir_ / "anew.glb"));
  const json& before = source.doc["meshes"][0]["primitives"][0];
  const json& after = kept.doc["meshes"][0]["primitives"][0];
  ASSERT_EQ(after["extras"]["tangentFieldDesigner"]["stripePhaseTexCoord"], 2);
  ASSERT_TRUE(after["attributes"].contains("TEXCOORD_2"));
  const std::vector<uint32_t> from = indicesOf(source, before), to = indicesOf(kept, after),
                              anewCorners = indicesOf(anew, anew.doc["meshes"][0]["primitives"][0]);
  ASSERT_EQ(to.size(), from.size());
  ASSERT_EQ(anewCorners.size(), from.size());
  const size_t sourceVertices = source.doc["accessors"][before["attributes"]["POSITION"].get<int>()]["count"];
  const size_t keptVertices = kept.doc["accessors"][after["attributes"]["POSITION"].get<int>()]["count"];
  std::cout << "[ measured ] kept layout: " << sourceVertices << " vertices split into " << keptVertices
            << "\n";
  EXPECT_GT(keptVertices, sourceVertices);  // the branch points' faces could not share their corners
  size_t mismatches = 0;
  for (size_t c = 0; c < from.size(); ++c) {
    for (const char* name : {"POSITION", "TEXCOORD_0", "TEXCOORD_1", "COLOR_0"})
      mismatches += elementBytes(source, before["attributes"][name].get<int>(), from[c]) !=
                    elementBytes(kept, after["attributes"][name].get<int>(), to[c]);
    mismatches += elementBytes(source, before["targets"][0]["POSITION"].get<int>(), from[c]) !=
                  elementBytes(kept, after["targets"][0]["POSITION"].get<int>(), to[c]);
    mismatches +=
        elementBytes(kept, after["attributes"]["TEXCOORD_2"].get<int>(), to[c]) !=
        elementBytes(anew, anew.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"].get<int>(),
                     anewCorners[c]);
  }
  EXPECT_EQ(mismatches, 0u);
  const json& bounds = kept.doc["accessors"][after["attributes"]["POSITION"].get<int>()];
  EXPECT_EQ(bounds["min"], source.doc["accessors"][before["attributes"]["POSITION"].get<int>()]["min"]);
  const SurfaceMesh reopened = tvf::loadMesh(path("kept.glb"));
  EXPECT_EQ(reopened.positions, mesh_.positions);
  EXPECT_EQ(reopened.triangles, mesh_.triangles);
}

TEST_F(CurvedPatchExport, NormalMappedMaterialsGetTheDirectionInAnisotropyTexture) {
  const double worst = anisotropyTextureDeviation("design.json", "mapped.out.glb", false);
  EXPECT_LT(worst, 2.0);
  std::cout << "[ measured ] anisotropyTexture worst deviation from the stroke: " << worst << " deg\n";
}

// Line and cross fields (symmetry N >= 2) leave in the same GLB, combed per chart: the direction a viewer's
// KHR_materials_anisotropy uses (TANGENT, or anisotropyTexture for normal-mapped materials), decoded, within
// 5 degrees of the stroke modulo pi at the faces it crosses; and as Directional's raw field.
double degreesModPi(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double d = degreesBetween(a, b);
  return std::min(d, 180 - d);
}

TEST_F(CurvedPatchExport, LineFieldAnisotropyFollowsTheStrokeModuloPi) {
  json line = design_;
  line["symmetry"] = 2;
  std::ofstream(dir_ / "line.json") << line.dump();
  ASSERT_EQ(
      runCli(path("patch.glb") + " " + path("line.json") + " --glb " + path("line.glb") + " --size 128"), 0);
  const Glb out = parseGlb(readBytes(dir_ / "line.glb"));
  const json& primitive = out.doc["meshes"][0]["primitives"][0];
  EXPECT_TRUE(out.doc["materials"][0]["extensions"].contains("KHR_materials_anisotropy"));
  EXPECT_EQ(out.doc["extras"][tvf::kGlbExtrasKey]["design"]["symmetry"], 2);
  const std::vector<float> tangents = accessorFloats(out, primitive["attributes"]["TANGENT"].get<int>());
  double worst = 0;
  for (size_t k = 0; k + 1 < stroke_.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const int32_t v = mesh_.triangles[3 * stroke_[k].face + c];
      const Eigen::Vector3d t(tangents[4 * v], tangents[4 * v + 1], tangents[4 * v + 2]);
      const Eigen::Vector3d n = tvf::faceNormal(mesh_, stroke_[k].face), along = strokeTangent(k);
      worst = std::max(worst, degreesModPi(t - n.dot(t) * n, along - n.dot(along) * n));
    }
  EXPECT_LT(worst, 5.0);
  std::cout << "[ measured ] line field TANGENT worst deviation from the stroke (mod pi): " << worst
            << " deg\n";

  const double worstTexture = anisotropyTextureDeviation("line.json", "mapped.line.glb", true);
  EXPECT_LT(worstTexture, 5.0);
  std::cout << "[ measured ] line field anisotropyTexture worst deviation (mod pi): " << worstTexture
            << " deg\n";
}

TEST_F(CurvedPatchExport, CrossFieldRawFieldReadsBackTheSameDirections) {
  json cross = design_;
  cross["symmetry"] = 4;
  std::ofstream(dir_ / "cross.json") << cross.dump();
  ASSERT_EQ(runCli(path("patch.glb") + " " + path("cross.json") + " --rawfield " + path("cross.rawfield") +
                   " --glb " + path("cross.glb") + " --size 64"),
            0);
  const std::vector<uint8_t> bytes = readBytes(dir_ / "cross.rawfield");
  const tvf::RawField raw = tvf::readRawField(std::string(bytes.begin(), bytes.end()));
  ASSERT_EQ(raw.symmetry, 4);
  ASSERT_EQ(raw.directions.size(), 12u * mesh_.numFaces());
  tvf::Designer d(mesh_);
  tvf::applyDesignDocument(d, cross);
  d.solve();
  double worst = 0, worstRight = 0;
  for (int32_t f = 0; f < mesh_.numFaces(); ++f) {
    const Eigen::Vector3d n = tvf::faceNormal(mesh_, f), rep(&d.faceVectors()[3 * f]);
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d w(&raw.directions[12 * f + 3 * k]);
      EXPECT_NEAR(w.norm(), 1, 1e-9);
      EXPECT_NEAR(w.dot(n), 0, 1e-9);
      worst = std::max(worst, std::abs(tvf::symmetricAngle(rep, w, n, 4)));
      // Counter-clockwise order: each direction is the previous one turned by +pi/2 about the normal.
      const Eigen::Vector3d next(&raw.directions[12 * f + 3 * ((k + 1) % 4)]);
      worstRight = std::max(worstRight, (n.cross(w) - next).norm());
    }
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(worstRight, 1e-9);
  EXPECT_THROW(tvf::readRawField("4 2\n1 0 0"), tvf::InputError);
  EXPECT_THROW(tvf::readRawField("hello"), tvf::InputError);
}

}  // namespace

// export --stripes writes the phase as TEXCOORD_1 on a GLB it builds anew (an OFF model: a generated atlas).
// A flat square with a constant field along x: the first coordinate is the phase in periods, so it changes
// along y at exactly the asked frequency and not along x (within 10^-3 of a period), and a flat field's phase
// has no seam: every corner at one position carries the same value.
TEST(StripeExport, ThePhaseIsWrittenAsASecondTextureCoordinate) {
  const fs::path dir = fs::temp_directory_path() / ("tvf_stripe_tex_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const tvf::SurfaceMesh m = tvf::testing::flatGrid(12, 1.0, true);
  {
    std::ofstream off(dir / "square.off");
    off << "OFF\n" << m.numVertices() << " " << m.numFaces() << " 0\n";
    for (int32_t v = 0; v < m.numVertices(); ++v)
      off << m.positions[3 * v] << " " << m.positions[3 * v + 1] << " " << m.positions[3 * v + 2] << "\n";
    for (int32_t f = 0; f < m.numFaces(); ++f)
      off << "3 " << m.triangles[3 * f] << " " << m.triangles[3 * f + 1] << " " << m.triangles[3 * f + 2]
          << "\n";
    std::ofstream(dir / "design.json")
        << json{{"constraints", {{{"type", "vector"}, {"face", 0}, {"vector", {1, 0, 0}}}}}}.dump();
  }
  const double frequency = 3.0;
  ASSERT_EQ(runCli((dir / "square.off").string() + " " + (dir / "design.json").string() + " --glb " +
                   (dir / "s.glb").string() + " --stripes 3 --size 256"),
            0);
  const Glb glb = parseGlb(readBytes(dir / "s.glb"));
  const json& attributes = glb.doc["meshes"][0]["primitives"][0]["attributes"];
  ASSERT_TRUE(attributes.contains("TEXCOORD_1"));
  const std::vector<float> p = accessorFloats(glb, attributes["POSITION"].get<int>());
  const std::vector<float> phase = accessorFloats(glb, attributes["TEXCOORD_1"].get<int>());
  ASSERT_EQ(phase.size() / 2, p.size() / 3);
  // phase = s * frequency * y + c, s = +-1 (which way the phase grows across the field).
  const double s = (phase[2] - phase[0]) * (p[4] - p[1]) >= 0 ? 1.0 : -1.0;
  const double c = phase[0] - s * frequency * p[1];
  std::map<std::pair<long, long>, float> at;
  double worst = 0, seams = 0;
  for (size_t v = 0; v < phase.size() / 2; ++v) {
    worst = std::max(worst, std::abs(phase[2 * v] - s * frequency * p[3 * v + 1] - c));
    const auto key = std::make_pair(std::lround(1e5 * p[3 * v]), std::lround(1e5 * p[3 * v + 1]));
    const auto [it, fresh] = at.emplace(key, phase[2 * v]);
    if (!fresh) seams = std::max(seams, static_cast<double>(std::abs(it->second - phase[2 * v])));
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(seams, 1e-4);
  fs::remove_all(dir);
}
