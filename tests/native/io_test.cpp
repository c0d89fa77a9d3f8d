// Mesh loaders: every format on small inputs written here (glTF documents are assembled byte by byte), the
// error messages, and robustness against truncated and corrupted input.
#include <gtest/gtest.h>
#include <stdlib.h>  // mkdtemp

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "io/mesh_io.h"

namespace tvf {
namespace {

namespace fs = std::filesystem;

using Bytes = std::vector<uint8_t>;

Bytes toBytes(const std::string& text) {
  return Bytes(text.begin(), text.end());
}

SurfaceMesh loadText(const std::string& text, MeshFormat format, const std::string& baseDir = "") {
  const Bytes bytes = toBytes(text);
  return loadMeshFromMemory(bytes.data(), bytes.size(), format, baseDir);
}

// The message of the InputError that `load` throws; fails the test if it throws nothing or something else.
std::string errorOf(const std::function<void()>& load) {
  try {
    load();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return "";
}

std::string textError(const std::string& text, MeshFormat format) {
  return errorOf([&] { loadText(text, format); });
}

// A fresh directory under the system temp dir, removed with everything in it at the end of the test.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "tvf_io_test_XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const Bytes& bytes) const {
    std::ofstream out(file(name), std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return file(name);
  }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

// ---- glTF assembly -------------------------------------------------------------------------------------

constexpr int kUByte = 5121, kUShort = 5123, kUInt = 5125, kFloat = 5126;

// Little-endian on every host we build for (x86-64, wasm).
template <class T>
Bytes bytesOf(const std::vector<T>& values) {
  Bytes bytes(values.size() * sizeof(T));
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

std::string base64(const Bytes& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t chunk = uint32_t{bytes[i]} << 16 |
                           (i + 1 < bytes.size() ? uint32_t{bytes[i + 1]} << 8 : 0) |
                           (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

void appendLE32(Bytes& out, uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(value >> (8 * i)));
}

// Collects buffer views and accessors over one binary buffer and writes the document around them.
class GltfBuilder {
 public:
  int view(const Bytes& bytes, int stride = 0) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    std::string json = "{\"buffer\":0,\"byteOffset\":" + std::to_string(bin_.size()) +
                       ",\"byteLength\":" + std::to_string(bytes.size());
    if (stride > 0) json += ",\"byteStride\":" + std::to_string(stride);
    views_.push_back(json + "}");
    bin_.insert(bin_.end(), bytes.begin(), bytes.end());
    return static_cast<int>(views_.size()) - 1;
  }
  int accessor(int view, int componentType, int count, const std::string& type, int offset = 0,
               const std::string& extra = "") {
    std::string json = "{";
    if (view >= 0) json += "\"bufferView\":" + std::to_string(view) + ",";
    json += "\"byteOffset\":" + std::to_string(offset) +
            ",\"componentType\":" + std::to_string(componentType) + ",\"count\":" + std::to_string(count) +
            ",\"type\":\"" + type + "\"" + extra + "}";
    accessors_.push_back(json);
    return static_cast<int>(accessors_.size()) - 1;
  }
  void setMeshes(const std::string& json) { meshes_ = json; }
  // Everything after "meshes" at the top level: nodes, scenes, scene.
  void setScene(const std::string& json) { scene_ = json; }

  const Bytes& bin() const { return bin_; }
  // uri empty: the buffer is the GLB's BIN chunk.
  std::string json(const std::string& uri) const {
    std::string json =
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":" + std::to_string(bin_.size());
    if (!uri.empty()) json += ",\"uri\":\"" + uri + "\"";
    json += "}],\"bufferViews\":" + list(views_) + ",\"accessors\":" + list(accessors_) +
            ",\"meshes\":" + meshes_;
    if (!scene_.empty()) json += "," + scene_;
    return json + "}";
  }
  std::string embeddedJson() const { return json("data:application/octet-stream;base64," + base64(bin_)); }
  Bytes glb() const {
    std::string json = this->json("");
    while (json.size() % 4 != 0) json += ' ';
    Bytes bin = bin_;
    while (bin.size() % 4 != 0) bin.push_back(0);
    Bytes out = toBytes("glTF");
    appendLE32(out, 2);
    appendLE32(out, static_cast<uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    appendLE32(out, static_cast<uint32_t>(json.size()));
    appendLE32(out, 0x4E4F534Au);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    appendLE32(out, static_cast<uint32_t>(bin.size()));
    appendLE32(out, 0x004E4942u);  // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
    return out;
  }

 private:
  static std::string list(const std::vector<std::string>& items) {
    std::string out = "[";
    for (std::size_t i = 0; i < items.size(); ++i) out += (i ? "," : "") + items[i];
    return out + "]";
  }

  Bytes bin_;
  std::vector<std::string> views_;
  std::vector<std::string> accessors_;
  std::string meshes_ = "[]";
  std::string scene_;
};

// A unit square as two triangles with a UV seam along the diagonal (6 source vertices, 4 positions),
// interleaved position+uv with byteStride 20 and u16 indices; a line primitive that must be skipped; and a
// second mesh (one non-indexed triangle, no UVs) that no node instances.
// Node 0 (matrix: rotate 90 degrees about z, then translate by (10,0,0)) instances mesh 0 and has child node
// 1 (TRS: scale 2, translate (0,0,5)), which instances mesh 0 again.
GltfBuilder seamScene(bool withScenes = true) {
  GltfBuilder b;
  const std::vector<float> interleaved = {0, 0, 0, 0,   0, 1, 0, 0, 1,   0, 1, 1, 0, 1, 1,
                                          0, 0, 0, 0.5, 0, 1, 1, 0, 0.5, 1, 0, 1, 0, 0, 1};
  const int vertexView = b.view(bytesOf(interleaved), 20);
  const int indexView = b.view(bytesOf<uint16_t>({0, 1, 2, 3, 4, 5}));
  const int otherView = b.view(bytesOf<float>({5, 5, 5, 6, 5, 5, 5, 6, 5}));
  b.accessor(vertexView, kFloat, 6, "VEC3");      // 0: POSITION
  b.accessor(vertexView, kFloat, 6, "VEC2", 12);  // 1: TEXCOORD_0
  b.accessor(indexView, kUShort, 6, "SCALAR");    // 2: indices
  b.accessor(otherView, kFloat, 3, "VEC3");       // 3: POSITION of mesh 1
  b.setMeshes(R"([{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2},
                                 {"attributes":{"POSITION":0},"mode":1}]},
                  {"primitives":[{"attributes":{"POSITION":3}}]}])");
  if (withScenes) {
    b.setScene(R"("nodes":[{"matrix":[0,1,0,0, -1,0,0,0, 0,0,1,0, 10,0,0,1],"mesh":0,"children":[1]},
                           {"translation":[0,0,5],"scale":[2,2,2],"mesh":0}],
                  "scenes":[{"nodes":[0]}],"scene":0)");
  }
  return b;
}

void expectSeamScene(const SurfaceMesh& mesh) {
  const std::vector<double> positions = {10, 0, 0, 10, 1, 0, 9, 1, 0, 9, 0, 0,   // node 0
                                         10, 0, 5, 10, 2, 5, 8, 2, 5, 8, 0, 5};  // node 1
  EXPECT_EQ(mesh.numVertices(), 8);
  EXPECT_EQ(mesh.positions, positions);
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}));
  // 12 source vertices welded to 8: fewer welded than source vertices.
  EXPECT_EQ(mesh.sourceToWelded, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}));
  const std::vector<float> squareUVs = {0, 0, 1, 0, 1, 1, 0.5f, 0, 0.5f, 1, 0, 1};
  std::vector<float> uvs = squareUVs;
  uvs.insert(uvs.end(), squareUVs.begin(), squareUVs.end());
  EXPECT_EQ(mesh.cornerUVs, uvs);
}

TEST(MeshIoGltf, ExternalBufferFile) {
  TempDir dir;
  const GltfBuilder b = seamScene();
  dir.write("scene.bin", b.bin());
  const std::string path = dir.write("scene.gltf", toBytes(b.json("scene.bin")));
  expectSeamScene(loadMesh(path));
  // The same document from memory, with the folder given explicitly.
  expectSeamScene(loadText(b.json("scene.bin"), MeshFormat::Gltf, dir.path()));
}

TEST(MeshIoGltf, ExternalBufferInSubfolderWithEscapedName) {
  TempDir dir;
  const GltfBuilder b = seamScene();
  fs::create_directory(dir.file("bin"));
  dir.write("bin/my scene.bin", b.bin());
  const std::string path = dir.write("scene.gltf", toBytes(b.json("bin/my%20scene.bin")));
  expectSeamScene(loadMesh(path));
}

TEST(MeshIoGltf, EmbeddedDataUri) {
  expectSeamScene(loadText(seamScene().embeddedJson(), MeshFormat::Gltf));
}

TEST(MeshIoGltf, Glb) {
  const Bytes glb = seamScene().glb();
  expectSeamScene(loadMeshFromMemory(glb.data(), glb.size(), MeshFormat::Glb));
  TempDir dir;
  expectSeamScene(loadMesh(dir.write("scene.GLB", glb)));
}

TEST(MeshIoGltf, NoScenesTakesEveryMeshUntransformed) {
  const SurfaceMesh mesh = loadText(seamScene(false).embeddedJson(), MeshFormat::Gltf);
  EXPECT_EQ(mesh.positions,
            (std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 5, 5, 5, 6, 5, 5, 5, 6, 5}));
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 4, 5, 6}));
  EXPECT_EQ(mesh.sourceToWelded, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 4, 5, 6}));
  EXPECT_TRUE(mesh.cornerUVs.empty());  // mesh 1 has no TEXCOORD_0
}

TEST(MeshIoGltf, DefaultSceneIsRespected) {
  GltfBuilder b = seamScene();
  b.setScene(R"("nodes":[{"mesh":0},{"mesh":1,"translation":[1,2,3]}],
                "scenes":[{"nodes":[0]},{"nodes":[1]}],"scene":1)");
  const SurfaceMesh mesh = loadText(b.embeddedJson(), MeshFormat::Gltf);
  EXPECT_EQ(mesh.positions, (std::vector<double>{6, 7, 8, 7, 7, 8, 6, 8, 8}));
  EXPECT_EQ(mesh.numFaces(), 1);
}

TEST(MeshIoGltf, RotationQuaternion) {
  GltfBuilder b = seamScene();
  // 90 degrees about z.
  b.setScene(R"("nodes":[{"mesh":1,"rotation":[0,0,0.70710678118654752,0.70710678118654752]}],
                "scenes":[{"nodes":[0]}])");
  const SurfaceMesh mesh = loadText(b.embeddedJson(), MeshFormat::Gltf);
  const std::vector<double> expected = {-5, 5, 5, -5, 6, 5, -6, 5, 5};
  ASSERT_EQ(mesh.positions.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(mesh.positions[i], expected[i], 1e-12);
}

TEST(MeshIoGltf, StripFanAndNormalizedTexcoords) {
  GltfBuilder b;
  const int positions = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}));
  const int uvs = b.view(Bytes{0, 0, 255, 0, 0, 255, 255, 255});
  const int fanIndices = b.view(Bytes{0, 1, 3, 2});
  b.accessor(positions, kFloat, 4, "VEC3");
  b.accessor(uvs, kUByte, 4, "VEC2", 0, ",\"normalized\":true");
  b.accessor(fanIndices, kUByte, 4, "SCALAR");
  b.setMeshes(R"([{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"mode":5},
                                 {"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2,"mode":6}]}])");
  b.setScene(R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])");
  const SurfaceMesh mesh = loadText(b.embeddedJson(), MeshFormat::Gltf);
  EXPECT_EQ(mesh.numVertices(), 4);
  // Strip 0 1 2 3: (0,1,2), (1,3,2). Fan over corners 0 1 3 2: (1,3,0), (3,2,0); the second primitive's
  // vertices weld onto the first's.
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, 2, 1, 3, 2, 1, 3, 0, 3, 2, 0}));
  EXPECT_EQ(mesh.sourceToWelded, (std::vector<int32_t>{0, 1, 2, 3, 0, 1, 2, 3}));
  EXPECT_EQ(mesh.cornerUVs, (std::vector<float>{0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 0, 1,  //
                                                1, 0, 1, 1, 0, 0, 1, 1, 0, 1, 0, 0}));
}

TEST(MeshIoGltf, SparseAccessor) {
  GltfBuilder b;
  const int positions = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}));
  const int sparseIndices = b.view(bytesOf<uint32_t>({2}));
  const int sparseValues = b.view(bytesOf<float>({0, 3, 4}));
  b.accessor(positions, kFloat, 3, "VEC3", 0,
             ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" + std::to_string(sparseIndices) +
                 ",\"componentType\":5125},\"values\":{\"bufferView\":" + std::to_string(sparseValues) +
                 "}}");
  b.setMeshes(R"([{"primitives":[{"attributes":{"POSITION":0}}]}])");
  const SurfaceMesh mesh = loadText(b.embeddedJson(), MeshFormat::Gltf);
  EXPECT_EQ(mesh.positions, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 3, 4}));
}

TEST(MeshIoGltf, DegenerateFacesAreKept) {
  GltfBuilder b;
  const int positions = b.view(bytesOf<float>({0, 0, 0, 0, 0, 0, 1, 0, 0}));
  const int indices = b.view(bytesOf<uint32_t>({2, 1, 0}));
  b.accessor(positions, kFloat, 3, "VEC3");
  b.accessor(indices, kUInt, 3, "SCALAR");
  b.setMeshes(R"([{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}])");
  const SurfaceMesh mesh = loadText(b.embeddedJson(), MeshFormat::Gltf);
  EXPECT_EQ(mesh.numVertices(), 2);
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{1, 0, 0}));
  EXPECT_EQ(mesh.sourceToWelded, (std::vector<int32_t>{0, 0, 1}));
}

// A document with a single triangle primitive whose pieces the error tests replace.
GltfBuilder triangleDoc(const std::string& primitive, int positionCount = 3) {
  GltfBuilder b;
  const int positions = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}));
  const int indices = b.view(bytesOf<uint16_t>({0, 1, 7, 0}));
  b.accessor(positions, kFloat, positionCount, "VEC3");
  b.accessor(indices, kUShort, 3, "SCALAR");
  b.setMeshes("[{\"primitives\":[" + primitive + "]}]");
  return b;
}

std::string gltfError(const GltfBuilder& b) {
  return textError(b.embeddedJson(), MeshFormat::Gltf);
}

TEST(MeshIoGltfErrors, NoTrianglePrimitives) {
  const std::string message = gltfError(triangleDoc(R"({"attributes":{"POSITION":0},"mode":1})"));
  EXPECT_NE(message.find("glTF data"), std::string::npos) << message;
  EXPECT_NE(message.find("no triangle primitives"), std::string::npos) << message;
}

TEST(MeshIoGltfErrors, NoPosition) {
  const std::string message = gltfError(triangleDoc(R"({"attributes":{"NORMAL":0}})"));
  EXPECT_NE(message.find("POSITION"), std::string::npos) << message;
}

TEST(MeshIoGltfErrors, AccessorOutOfBounds) {
  const std::string message = gltfError(triangleDoc(R"({"attributes":{"POSITION":0}})", 4));
  EXPECT_NE(message.find("out of bounds"), std::string::npos) << message;
}

TEST(MeshIoGltfErrors, IndexOutOfRange) {
  const std::string message = gltfError(triangleDoc(R"({"attributes":{"POSITION":0},"indices":1})"));
  EXPECT_NE(message.find("out of range"), std::string::npos) << message;
}

TEST(MeshIoGltfErrors, NodeCycle) {
  GltfBuilder b = triangleDoc(R"({"attributes":{"POSITION":0}})");
  b.setScene(R"("nodes":[{"mesh":0,"children":[1]},{"children":[0]}],"scenes":[{"nodes":[0]}])");
  const std::string message = gltfError(b);
  EXPECT_NE(message.find("reached twice"), std::string::npos) << message;
}

TEST(MeshIoGltfErrors, ExternalBufferWithoutBaseDir) {
  const std::string message = textError(seamScene().json("scene.bin"), MeshFormat::Gltf);
  EXPECT_NE(message.find("scene.bin"), std::string::npos) << message;
  EXPECT_NE(message.find("base directory"), std::string::npos) << message;
}

TEST(MeshIoGltfErrors, MissingExternalBuffer) {
  TempDir dir;
  const std::string path = dir.write("scene.gltf", toBytes(seamScene().json("missing.bin")));
  const std::string message = errorOf([&] { loadMesh(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("missing.bin"), std::string::npos) << message;
}

TEST(MeshIoGltfErrors, TruncatedGlb) {
  const Bytes glb = seamScene().glb();
  const std::string message =
      errorOf([&] { loadMeshFromMemory(glb.data(), glb.size() - 4, MeshFormat::Glb); });
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
}

TEST(MeshIoGltfErrors, InvalidJson) {
  EXPECT_NE(textError("{\"asset\": ", MeshFormat::Gltf).find("invalid glTF"), std::string::npos);
}

TEST(MeshIoGltfErrors, DeeplyNestedJson) {
  const std::string json = "{\"asset\":{\"version\":\"2.0\",\"extras\":" + std::string(100000, '[') +
                           std::string(100000, ']') + "}}";
  EXPECT_NE(textError(json, MeshFormat::Gltf).find("nested"), std::string::npos);
}

// ---- OFF -----------------------------------------------------------------------------------------------

TEST(MeshIoOff, ShippedFile) {
  const SurfaceMesh mesh = loadMesh(std::string(TVF_TEST_DATA_DIR) + "/io_square.off");
  EXPECT_EQ(mesh.positions, (std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1}));
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 0, 1, 4, 0, 4, 3}));
  EXPECT_TRUE(mesh.cornerUVs.empty());
  EXPECT_TRUE(mesh.sourceToWelded.empty());
}

TEST(MeshIoOff, CountsOnHeaderLineColorsAndOutOfRangeIndices) {
  const SurfaceMesh mesh = loadText(
      "COFF 3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n"
      "3 0 1 7 200 200 200\n",
      MeshFormat::Off);
  EXPECT_EQ(mesh.numVertices(), 3);
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, 7}));  // left for the topology checks
}

TEST(MeshIoOff, NanAndInfAreNotLoaderErrors) {
  const SurfaceMesh mesh = loadText("OFF\n3 1\nnan 0 0\ninf 0 0\n0 -inf 0\n3 0 1 2\n", MeshFormat::Off);
  EXPECT_TRUE(std::isnan(mesh.positions[0]));
  EXPECT_TRUE(std::isinf(mesh.positions[3]));
  EXPECT_TRUE(std::isinf(mesh.positions[7]) && mesh.positions[7] < 0);
}

TEST(MeshIoOff, Errors) {
  EXPECT_NE(textError("OFF\n3 1\n0 0 0\n1 0 x\n", MeshFormat::Off).find("OFF data:4:"), std::string::npos);
  EXPECT_NE(textError("OFF\n3 1\n0 0 0\n1 0 x\n", MeshFormat::Off).find("not a number"), std::string::npos);
  EXPECT_NE(textError("OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", MeshFormat::Off)
                .find(":6: face 0 has fewer than 3"),
            std::string::npos);
  EXPECT_NE(textError("OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n", MeshFormat::Off).find("not an integer"),
            std::string::npos);
  EXPECT_NE(textError("OFF\n3 1\n0 0 0\n1 0 0\n", MeshFormat::Off).find("unexpected end of file"),
            std::string::npos);
  EXPECT_NE(textError("  \n# only a comment\n", MeshFormat::Off).find("empty"), std::string::npos);
  EXPECT_NE(textError("OFF\n3 0\n0 0 0\n1 0 0\n0 1 0\n", MeshFormat::Off).find("no faces"),
            std::string::npos);
  EXPECT_NE(textError("hello\n", MeshFormat::Off).find("not an OFF file"), std::string::npos);
}

// ---- OBJ -----------------------------------------------------------------------------------------------

TEST(MeshIoObj, ShippedFileWithQuadsAndNegativeIndices) {
  const SurfaceMesh mesh = loadMesh(std::string(TVF_TEST_DATA_DIR) + "/io_quads.obj");
  EXPECT_EQ(mesh.positions, (std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0}));
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2}));
  EXPECT_TRUE(mesh.cornerUVs.empty());
}

TEST(MeshIoObj, CornerFormsAndUVs) {
  const std::string obj =
      "# comment\r\n"
      "mtllib x.mtl\r\no thing\r\n"
      "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0 1.0\r\n"
      "vt 0 0\r\nvt 1 0\r\nvt 1 1\r\nvt 0 1\r\n"
      "vn 0 0 1\r\n"
      "usemtl a\r\ns off\r\n"
      "f 1/1/1 2/2/1 3/3/1 4/4/1\r\n"  // quad, v/vt/vn
      "f -4/-4 -2/-2 -1/-1\r\n";       // v/vt with negative indices
  const SurfaceMesh mesh = loadText(obj, MeshFormat::Obj);
  EXPECT_EQ(mesh.numVertices(), 4);
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 0, 2, 3}));
  EXPECT_EQ(mesh.cornerUVs, (std::vector<float>{0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1, 0, 0, 1, 1, 0, 1}));
}

TEST(MeshIoObj, UVsDroppedWhenACornerHasNone) {
  const SurfaceMesh mesh =
      loadText("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1//1 2//1 3//1\n", MeshFormat::Obj);
  EXPECT_EQ(mesh.numFaces(), 2);
  EXPECT_TRUE(mesh.cornerUVs.empty());
}

TEST(MeshIoObj, OutOfRangeIndicesPassThrough) {
  const SurfaceMesh mesh = loadText("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\nf 0 -5 3\n", MeshFormat::Obj);
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, 8, -1, -2, 2}));
}

TEST(MeshIoObj, Errors) {
  const std::string badNumber = textError("v 0 0 0\nv 1 0 0\nv 1 abc 0\n", MeshFormat::Obj);
  EXPECT_NE(badNumber.find("OBJ data:3:"), std::string::npos) << badNumber;
  EXPECT_NE(badNumber.find("not a number"), std::string::npos) << badNumber;
  EXPECT_NE(textError("v 0 0 0\nv 1 0 0\nf 1 2\n", MeshFormat::Obj).find(":3: face with fewer than 3"),
            std::string::npos);
  EXPECT_NE(textError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", MeshFormat::Obj).find("not an integer"),
            std::string::npos);
  EXPECT_NE(textError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3.0\n", MeshFormat::Obj).find("not an integer"),
            std::string::npos);
  EXPECT_NE(textError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n", MeshFormat::Obj).find("out of range"),
            std::string::npos);
  EXPECT_NE(textError("v 0 0\n", MeshFormat::Obj).find("missing z"), std::string::npos);
  EXPECT_NE(textError("\n\n# nothing\n", MeshFormat::Obj).find("empty"), std::string::npos);
  EXPECT_NE(textError("v 0 0 0\n", MeshFormat::Obj).find("no faces"), std::string::npos);
}

// ---- PLY -----------------------------------------------------------------------------------------------

enum class Encoding { Ascii, Little, Big };

// Writes typed values in one of the three PLY encodings.
class PlyWriter {
 public:
  explicit PlyWriter(Encoding encoding) : encoding_(encoding) {}

  template <class T>
  PlyWriter& put(T value) {
    if (encoding_ == Encoding::Ascii) {
      if (!atLineStart_) text_ += ' ';
      text_ += std::is_floating_point_v<T> ? formatFloat(value) : std::to_string(+value);
      atLineStart_ = false;
      return *this;
    }
    uint8_t raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (encoding_ == Encoding::Big) std::reverse(raw, raw + sizeof(T));
    text_.append(reinterpret_cast<const char*>(raw), sizeof(T));
    return *this;
  }
  PlyWriter& endItem() {
    if (encoding_ == Encoding::Ascii) text_ += '\n';
    atLineStart_ = true;
    return *this;
  }
  const std::string& body() const { return text_; }

 private:
  static std::string formatFloat(double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return buffer;
  }

  Encoding encoding_;
  std::string text_;
  bool atLineStart_ = true;
};

// A unit square (one quad) plus a triangle, with extra vertex properties, an unknown element with a list
// between vertices and faces, and a face property after the index list.
std::string plyFile(Encoding encoding) {
  const char* format = encoding == Encoding::Ascii    ? "ascii"
                       : encoding == Encoding::Little ? "binary_little_endian"
                                                      : "binary_big_endian";
  std::string header = std::string("ply\r\nformat ") + format +
                       " 1.0\r\n"
                       "comment made by hand\r\n"
                       "obj_info nothing\r\n"
                       "element vertex 5\r\n"
                       "property float x\r\n"
                       "property uchar red\r\n"
                       "property double y\r\n"
                       "property list uchar float extra\r\n"
                       "property short z\r\n"
                       "element material 2\r\n"
                       "property list int ushort ids\r\n"
                       "property float shininess\r\n"
                       "element face 2\r\n"
                       "property list uchar uint vertex_indices\r\n"
                       "property int flags\r\n"
                       "end_header\r\n";
  PlyWriter w(encoding);
  const double xyz[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, -2.25, 3}};
  for (const auto& p : xyz) {
    w.put(static_cast<float>(p[0])).put(uint8_t{200}).put(p[1]);
    w.put(uint8_t{2}).put(1.5f).put(-1.0f).put(static_cast<int16_t>(p[2])).endItem();
  }
  w.put(int32_t{3}).put(uint16_t{1}).put(uint16_t{2}).put(uint16_t{3}).put(0.25f).endItem();
  w.put(int32_t{0}).put(0.5f).endItem();
  w.put(uint8_t{4})
      .put(uint32_t{0})
      .put(uint32_t{1})
      .put(uint32_t{2})
      .put(uint32_t{3})
      .put(int32_t{-7})
      .endItem();
  w.put(uint8_t{3}).put(uint32_t{1}).put(uint32_t{4}).put(uint32_t{2}).put(int32_t{0}).endItem();
  return header + w.body();
}

void expectPlyMesh(const SurfaceMesh& mesh) {
  EXPECT_EQ(mesh.positions, (std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, -2.25, 3}));
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 1, 4, 2}));
}

TEST(MeshIoPly, AsciiAndBothBinaryEncodingsGiveTheSameMesh) {
  const SurfaceMesh ascii = loadText(plyFile(Encoding::Ascii), MeshFormat::Ply);
  const SurfaceMesh little = loadText(plyFile(Encoding::Little), MeshFormat::Ply);
  const SurfaceMesh big = loadText(plyFile(Encoding::Big), MeshFormat::Ply);
  expectPlyMesh(ascii);
  expectPlyMesh(little);
  expectPlyMesh(big);
  EXPECT_EQ(ascii.positions, big.positions);
  EXPECT_EQ(little.triangles, big.triangles);
}

TEST(MeshIoPly, VertexIndexNameAndSignedCounts) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\nproperty int y\nproperty int z\n"
      "element face 1\nproperty list int int vertex_index\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 -5\n";
  const SurfaceMesh mesh = loadText(ply, MeshFormat::Ply);
  EXPECT_EQ(mesh.positions, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(mesh.triangles, (std::vector<int32_t>{0, 1, -5}));
}

TEST(MeshIoPly, Errors) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string badNumber = textError(head + "0 0 0\n1 0 0\n0 q 0\n3 0 1 2\n", MeshFormat::Ply);
  EXPECT_NE(badNumber.find("PLY data:12:"), std::string::npos) << badNumber;
  EXPECT_NE(badNumber.find("not a number"), std::string::npos) << badNumber;
  EXPECT_NE(textError(head + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", MeshFormat::Ply).find("fewer than 3"),
            std::string::npos);
  EXPECT_NE(textError(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 b\n", MeshFormat::Ply).find("not an integer"),
            std::string::npos);
  EXPECT_NE(textError(head + "0 0 0\n1 0 0\n", MeshFormat::Ply).find("unexpected end of file"),
            std::string::npos);
  EXPECT_NE(textError("ply\nformat ascii 1.0\nelement vertex 3\n", MeshFormat::Ply).find("no end_header"),
            std::string::npos);
  EXPECT_NE(textError("ply\nformat ascii 1.0\nbogus line\nend_header\n", MeshFormat::Ply)
                .find(":3: unknown header"),
            std::string::npos);
  EXPECT_NE(
      textError("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header\n", MeshFormat::Ply)
          .find("no 'y'"),
      std::string::npos);
  EXPECT_NE(textError("solid\n", MeshFormat::Ply).find("not a PLY file"), std::string::npos);

  const std::string binary = plyFile(Encoding::Little);
  const std::string truncated = textError(binary.substr(0, binary.size() - 3), MeshFormat::Ply);
  EXPECT_NE(truncated.find("truncated"), std::string::npos) << truncated;
}

// ---- Dispatch and file errors --------------------------------------------------------------------------

TEST(MeshIoDispatch, FormatFromPath) {
  EXPECT_EQ(formatFromPath("a/b.gltf"), MeshFormat::Gltf);
  EXPECT_EQ(formatFromPath("B.GLB"), MeshFormat::Glb);
  EXPECT_EQ(formatFromPath("x.Off"), MeshFormat::Off);
  EXPECT_EQ(formatFromPath("dir.ply/x.obj"), MeshFormat::Obj);
  EXPECT_EQ(formatFromPath("x.tar.ply"), MeshFormat::Ply);
  const std::string unknown = errorOf([] { formatFromPath("model.stl"); });
  EXPECT_NE(unknown.find("model.stl"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("extension"), std::string::npos) << unknown;
  EXPECT_NE(errorOf([] { formatFromPath("dir.obj/model"); }).find("extension"), std::string::npos);
}

TEST(MeshIoDispatch, FormatFromBytes) {
  const auto sniff = [](const std::string& text) {
    const Bytes bytes = toBytes(text);
    return formatFromBytes(bytes.data(), bytes.size());
  };
  EXPECT_EQ(sniff("glTF\x02"), MeshFormat::Glb);
  EXPECT_EQ(sniff(" \n\t{\"asset\":{}}"), MeshFormat::Gltf);
  EXPECT_EQ(sniff("OFF\n"), MeshFormat::Off);
  EXPECT_EQ(sniff("NOFF\n"), MeshFormat::Off);
  EXPECT_EQ(sniff("ply\n"), MeshFormat::Ply);
  EXPECT_EQ(sniff("v 1 2 3\n"), MeshFormat::Obj);
  EXPECT_EQ(sniff(""), MeshFormat::Obj);
  EXPECT_EQ(formatFromBytes(nullptr, 0), MeshFormat::Obj);
}

TEST(MeshIoDispatch, FileErrors) {
  TempDir dir;
  const std::string missing = dir.file("missing.obj");
  const std::string notFound = errorOf([&] { loadMesh(missing); });
  EXPECT_NE(notFound.find(missing), std::string::npos) << notFound;
  EXPECT_NE(notFound.find("not found"), std::string::npos) << notFound;

  fs::create_directory(dir.file("folder.off"));
  EXPECT_NE(errorOf([&] { loadMesh(dir.file("folder.off")); }).find("cannot be read"), std::string::npos);

  const std::string empty = dir.write("empty.ply", {});
  const std::string emptyMessage = errorOf([&] { loadMesh(empty); });
  EXPECT_NE(emptyMessage.find(empty), std::string::npos) << emptyMessage;
  EXPECT_NE(emptyMessage.find("empty file"), std::string::npos) << emptyMessage;

  const std::string obj = dir.write("bad.obj", toBytes("v 0 0 0\nf 1 1\n"));
  EXPECT_NE(errorOf([&] { loadMesh(obj); }).find(obj + ":2:"), std::string::npos);

  for (MeshFormat format :
       {MeshFormat::Gltf, MeshFormat::Glb, MeshFormat::Off, MeshFormat::Obj, MeshFormat::Ply}) {
    EXPECT_NE(errorOf([&] { loadMeshFromMemory(nullptr, 0, format); }).find("empty file"), std::string::npos);
  }
}

// ---- Robustness ----------------------------------------------------------------------------------------

// Loading must either succeed or throw InputError: no other exception, no crash, no out-of-bounds read
// (the sanitizer build catches those).
void expectLoadsOrInputError(const Bytes& bytes, std::size_t size, MeshFormat format) {
  try {
    loadMeshFromMemory(bytes.data(), size, format);
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    ADD_FAILURE() << "format " << static_cast<int>(format) << ", " << size << " bytes: " << e.what();
  }
}

struct Sample {
  Bytes bytes;
  MeshFormat format;
};

std::vector<Sample> validSamples() {
  GltfBuilder sparse;
  const int positions = sparse.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}));
  const int sparseIndices = sparse.view(bytesOf<uint16_t>({1, 2}));
  const int sparseValues = sparse.view(bytesOf<float>({2, 0, 0, 0, 2, 0}));
  sparse.accessor(positions, kFloat, 3, "VEC3", 0,
                  ",\"sparse\":{\"count\":2,\"indices\":{\"bufferView\":" + std::to_string(sparseIndices) +
                      ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(sparseValues) +
                      "}}");
  sparse.setMeshes(R"([{"primitives":[{"attributes":{"POSITION":0}}]}])");
  return {
      {toBytes("OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 2 3 1\n"), MeshFormat::Off},
      {toBytes("v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 1\nf 1/1 2/2 3/1\nf -3//1 -2//1 -1//1\n"),
       MeshFormat::Obj},
      {toBytes(plyFile(Encoding::Ascii)), MeshFormat::Ply},
      {toBytes(plyFile(Encoding::Little)), MeshFormat::Ply},
      {toBytes(plyFile(Encoding::Big)), MeshFormat::Ply},
      {toBytes(seamScene().embeddedJson()), MeshFormat::Gltf},
      {toBytes(sparse.embeddedJson()), MeshFormat::Gltf},
      {seamScene().glb(), MeshFormat::Glb},
      {sparse.glb(), MeshFormat::Glb},
  };
}

TEST(MeshIoRobustness, SamplesLoad) {
  for (const Sample& sample : validSamples()) {
    EXPECT_NO_THROW(loadMeshFromMemory(sample.bytes.data(), sample.bytes.size(), sample.format));
    EXPECT_EQ(formatFromBytes(sample.bytes.data(), sample.bytes.size()), sample.format);
  }
}

TEST(MeshIoRobustness, EveryTruncatedPrefix) {
  for (const Sample& sample : validSamples()) {
    for (std::size_t size = 0; size <= sample.bytes.size(); ++size) {
      // A copy of exactly `size` bytes, so that the sanitizer sees any read past the end.
      const Bytes prefix(sample.bytes.begin(), sample.bytes.begin() + static_cast<std::ptrdiff_t>(size));
      expectLoadsOrInputError(prefix, prefix.size(), sample.format);
    }
  }
}

TEST(MeshIoRobustness, RandomByteFlips) {
  std::mt19937 random(12345);
  for (const Sample& sample : validSamples()) {
    for (int trial = 0; trial < 1500; ++trial) {
      Bytes corrupted = sample.bytes;
      const int flips = 1 + static_cast<int>(random() % 4);
      for (int f = 0; f < flips; ++f) {
        const std::size_t at = random() % corrupted.size();
        // Half the time a random byte, half the time a character that means something to the parsers.
        static const char kInteresting[] = "0123456789-+.e/#[]{}\",: \n\xff";
        corrupted[at] = random() % 2
                            ? static_cast<uint8_t>(random())
                            : static_cast<uint8_t>(kInteresting[random() % (sizeof kInteresting - 1)]);
      }
      expectLoadsOrInputError(corrupted, corrupted.size(), sample.format);
      expectLoadsOrInputError(corrupted, corrupted.size(),
                              formatFromBytes(corrupted.data(), corrupted.size()));
    }
  }
}

TEST(MeshIoRobustness, HostileCounts) {
  // Counts far beyond the data must fail on the data, not allocate for the count or loop forever.
  EXPECT_NE(textError("OFF\n99999999 1\n0 0 0\n", MeshFormat::Off).find("unexpected end"), std::string::npos);
  EXPECT_NE(
      textError("OFF\n3 99999999999\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::Off).find("unexpected end"),
      std::string::npos);
  EXPECT_NE(textError("ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
                      "property float y\nproperty float z\nelement face 1000000000\n"
                      "property list uint uint vertex_indices\nelement nothing 999999999999999\nend_header\n",
                      MeshFormat::Ply)
                .find("truncated"),
            std::string::npos);
  EXPECT_NE(
      textError("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uint uint vertex_indices\nend_header\n" +
                    std::string(36, '\0') + "\xff\xff\xff\xff",
                MeshFormat::Ply)
          .find("truncated"),
      std::string::npos);
  GltfBuilder unbacked;
  unbacked.accessor(-1, kFloat, 2000000000, "VEC3");
  unbacked.setMeshes(R"([{"primitives":[{"attributes":{"POSITION":0}}]}])");
  unbacked.view(Bytes{0, 0, 0, 0});
  EXPECT_NE(gltfError(unbacked).find("too large"), std::string::npos);
}

}  // namespace
}  // namespace tvf
