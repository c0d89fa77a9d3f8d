// glTF 2.0 (.gltf and .glb) through tinygltf. tinygltf parses the JSON and resolves buffers; everything
// after that (scene walk, accessor decoding, bounds checks, welding) is ours, because a hostile file must not
// make us read outside a buffer and tinygltf leaves those checks to the caller.
//
// These macros must match tinygltf_impl.cpp: they change inline members of tinygltf::TinyGLTF.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numeric>

#include "io/gltf_source.h"
#include "io/loaders.h"

namespace tvf::io_detail {
namespace {

using Mat4 = std::array<double, 16>;  // column-major, as glTF stores it
constexpr Mat4 kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

// tinygltf's JSON handling recurses on nesting (extras, extensions), so a file of a million '[' would blow
// the stack, and emscripten's stack is small. Real glTF nests less than a dozen levels.
constexpr int kMaxJsonDepth = 64;
// An accessor without a bufferView is all zeros (plus sparse values); its count is not bounded by any data,
// so bound it here to keep a tiny file from asking for gigabytes.
constexpr uint64_t kMaxUnbackedAccessorCount = uint64_t{1} << 24;

// ---- Loading the document ------------------------------------------------------------------------------

struct FsContext {
  std::string baseDir;
  std::string refusedPath;  // the first external file we declined to look up
};

bool fileExists(const std::string& path, void* user) {
  auto& context = *static_cast<FsContext*>(user);
  const std::string& dir = context.baseDir;
  const std::string prefix = dir.empty() || dir.back() == '/' ? dir : dir + "/";
  // tinygltf also probes the current directory; only files relative to the glTF's own folder may be read.
  if (dir.empty() || path.compare(0, prefix.size(), prefix) != 0) {
    if (context.refusedPath.empty()) context.refusedPath = path;
    return false;
  }
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

// The default expands environment variables and '~'; a URI in a file must not do that.
std::string expandFilePath(const std::string& path, void*) {
  return path;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *err = "cannot open file";
    return false;
  }
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return !in.bad();
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err = "writing is not supported";
  return false;
}

// Images are irrelevant to the field; accepting them unread keeps textured models loadable.
bool ignoreImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                 void*) {
  return true;
}

// tinygltf's messages are multi-line and may quote a whole data URI.
std::string cleanMessage(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  message = std::string(trim(message));
  constexpr std::size_t kMaxLength = 300;
  if (message.size() > kMaxLength) message = message.substr(0, kMaxLength) + "...";
  return message.empty() ? "unknown error" : message;
}

int jsonDepth(const char* text, std::size_t size) {
  int depth = 0;
  int maxDepth = 0;
  bool inString = false;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        inString = false;
      }
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      maxDepth = std::max(maxDepth, ++depth);
      if (maxDepth > kMaxJsonDepth) break;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return maxDepth;
}

uint32_t readLE32(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

// Validates the GLB container ourselves: tinygltf 2.7 lets a BIN chunk extend up to 8 bytes past the end of
// the data. Returns the JSON chunk and the GLB's declared length.
std::string_view checkGlbContainer(const uint8_t* data, std::size_t size, const std::string& name,
                                   uint32_t& length) {
  if (size < 12) fail(name, "truncated GLB header");
  if (std::memcmp(data, "glTF", 4) != 0) fail(name, "not a GLB file (bad magic)");
  if (readLE32(data + 4) != 2) fail(name, "unsupported GLB version " + std::to_string(readLE32(data + 4)));
  length = readLE32(data + 8);
  if (length > size) {
    fail(name,
         "truncated GLB: header declares " + std::to_string(length) + " bytes, got " + std::to_string(size));
  }
  if (length < 20) fail(name, "truncated GLB: no JSON chunk");
  const uint64_t jsonLength = readLE32(data + 12);
  if (readLE32(data + 16) != 0x4E4F534Au) fail(name, "first GLB chunk is not JSON");
  if (20 + jsonLength > length) fail(name, "truncated GLB: JSON chunk extends past the end");
  const uint64_t rest = length - 20 - jsonLength;
  if (rest > 0) {
    if (rest < 8) fail(name, "truncated GLB: incomplete BIN chunk header");
    const uint64_t binLength = readLE32(data + 20 + jsonLength);
    if (binLength > rest - 8) fail(name, "truncated GLB: BIN chunk extends past the end");
  }
  return std::string_view(reinterpret_cast<const char*>(data + 20), static_cast<std::size_t>(jsonLength));
}

void checkRequiredExtensions(const tinygltf::Model& model, const std::string& name) {
  for (const std::string& extension : model.extensionsRequired) {
    // Compressed geometry would need a decoder we do not ship; other required extensions (textures,
    // materials) do not change the geometry.
    if (extension == "KHR_draco_mesh_compression" || extension == "EXT_meshopt_compression" ||
        extension == "KHR_meshopt_compression") {
      fail(name, "requires unsupported extension " + quoteToken(extension));
    }
  }
}

tinygltf::Model parseModel(const uint8_t* data, std::size_t size, bool binary, const std::string& baseDir,
                           const std::string& name) {
  uint32_t glbLength = 0;
  const std::string_view json = binary ? checkGlbContainer(data, size, name, glbLength)
                                       : std::string_view(reinterpret_cast<const char*>(data), size);
  if (!binary && size > std::numeric_limits<unsigned int>::max()) fail(name, "file too large for glTF");
  if (jsonDepth(json.data(), json.size()) > kMaxJsonDepth) fail(name, "glTF JSON nested too deeply");

  FsContext context{baseDir, {}};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &context});
  loader.SetImageLoader(&ignoreImage, nullptr);
  tinygltf::Model model;
  std::string err;
  std::string warn;
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, glbLength, baseDir)
                : loader.LoadASCIIFromString(&model, &err, &warn, json.data(),
                                             static_cast<unsigned int>(size), baseDir);
  } catch (const std::exception& e) {
    // tinygltf reports most problems through err, but a few malformed inputs reach std::vector::at.
    fail(name, "invalid glTF (" + cleanMessage(e.what()) + ")");
  }
  if (!ok) {
    if (baseDir.empty() && !context.refusedPath.empty()) {
      fail(name, "external buffer " + quoteToken(context.refusedPath) +
                     " cannot be loaded without a base directory (embed it or load from a file)");
    }
    fail(name, "invalid glTF: " + cleanMessage(err));
  }
  checkRequiredExtensions(model, name);
  return model;
}

// ---- Scene walk ----------------------------------------------------------------------------------------

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 result{};
  for (int col = 0; col < 4; ++col) {
    for (int row = 0; row < 4; ++row) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) sum += a[k * 4 + row] * b[col * 4 + k];
      result[col * 4 + row] = sum;
    }
  }
  return result;
}

// T * R * S, with R from the unit quaternion (x, y, z, w).
Mat4 fromTRS(const std::vector<double>& t, const std::vector<double>& r, const std::vector<double>& s) {
  const double x = r.empty() ? 0.0 : r[0], y = r.empty() ? 0.0 : r[1];
  const double z = r.empty() ? 0.0 : r[2], w = r.empty() ? 1.0 : r[3];
  const double rotation[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                                 {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                                 {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  Mat4 m = kIdentity;
  for (int col = 0; col < 3; ++col) {
    const double scale = s.empty() ? 1.0 : s[col];
    for (int row = 0; row < 3; ++row) m[col * 4 + row] = rotation[row][col] * scale;
    m[12 + col] = t.empty() ? 0.0 : t[col];
  }
  return m;
}

Mat4 localTransform(const tinygltf::Node& node, int index, const std::string& name) {
  const auto badSize = [&](const char* what) {
    fail(name, "node " + std::to_string(index) + " has a malformed " + what);
  };
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) badSize("matrix");
    Mat4 m;
    std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
    return m;
  }
  if (!node.translation.empty() && node.translation.size() != 3) badSize("translation");
  if (!node.rotation.empty() && node.rotation.size() != 4) badSize("rotation");
  if (!node.scale.empty() && node.scale.size() != 3) badSize("scale");
  return fromTRS(node.translation, node.rotation, node.scale);
}

struct MeshInstance {
  int mesh;
  Mat4 transform;
};

// Meshes of the default scene in depth-first pre-order, with their world transforms (parent * child).
std::vector<MeshInstance> sceneInstances(const tinygltf::Model& model, const std::string& name) {
  std::vector<MeshInstance> instances;
  const auto checkMesh = [&](int mesh, int node) {
    if (mesh < 0 || static_cast<std::size_t>(mesh) >= model.meshes.size()) {
      fail(name, "node " + std::to_string(node) + " refers to missing mesh " + std::to_string(mesh));
    }
  };
  if (model.scenes.empty()) {
    for (std::size_t mesh = 0; mesh < model.meshes.size(); ++mesh) {
      instances.push_back({static_cast<int>(mesh), kIdentity});
    }
    return instances;
  }
  const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (static_cast<std::size_t>(sceneIndex) >= model.scenes.size()) {
    fail(name, "default scene " + std::to_string(sceneIndex) + " does not exist");
  }
  // glTF node hierarchies are forests; a node reached twice means a cycle or a shared child, and following
  // either could loop forever or explode combinatorially.
  std::vector<char> visited(model.nodes.size(), 0);
  std::vector<std::pair<int, Mat4>> stack;  // explicit, so a deep hierarchy cannot overflow the call stack
  const auto push = [&](int node, const Mat4& parent, int from) {
    if (node < 0 || static_cast<std::size_t>(node) >= model.nodes.size()) {
      fail(name, (from < 0 ? std::string("scene") : "node " + std::to_string(from)) +
                     " refers to missing node " + std::to_string(node));
    }
    if (visited[node]) fail(name, "node " + std::to_string(node) + " is reached twice (not a tree)");
    visited[node] = 1;
    stack.emplace_back(node, multiply(parent, localTransform(model.nodes[node], node, name)));
  };
  for (int root : model.scenes[sceneIndex].nodes) {
    push(root, kIdentity, -1);
    while (!stack.empty()) {
      const auto [index, transform] = stack.back();
      stack.pop_back();
      const tinygltf::Node& node = model.nodes[index];
      if (node.mesh >= 0) {
        checkMesh(node.mesh, index);
        instances.push_back({node.mesh, transform});
      }
      // Reverse, so that children pop in file order.
      for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
        push(*child, transform, index);
      }
    }
  }
  return instances;
}

// ---- Accessors -----------------------------------------------------------------------------------------

}  // namespace

std::size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

namespace {

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    default:
      return "another type";
  }
}

}  // namespace

// glTF data is little-endian whatever the host is.
double readComponent(const uint8_t* p, int componentType, bool normalized) {
  uint32_t bits = 0;
  for (std::size_t i = 0; i < componentSize(componentType); ++i) bits |= uint32_t{p[i]} << (8 * i);
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = static_cast<int8_t>(static_cast<uint8_t>(bits));
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? bits / 255.0 : bits;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = static_cast<int16_t>(static_cast<uint16_t>(bits));
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return normalized ? bits / 65535.0 : bits;
    case TINYGLTF_COMPONENT_TYPE_INT:
      return static_cast<int32_t>(bits);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return bits;
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float value;
      std::memcpy(&value, &bits, sizeof value);
      return value;
    }
    default:
      return 0.0;
  }
}

bool fits(uint64_t offset, uint64_t count, uint64_t stride, uint64_t elementSize, uint64_t available) {
  if (count == 0) return offset <= available;
  if (offset > available || available - offset < elementSize) return false;
  return count - 1 <= (available - offset - elementSize) / stride;
}

namespace {

struct Bytes {
  const uint8_t* data;
  uint64_t size;
};

class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, const std::string& name) : model_(model), name_(name) {}

  // All values of an accessor as doubles, count * components of them, sparse substitution applied.
  std::vector<double> read(int index, int expectedType, bool allowNormalized, const std::string& what) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) {
      fail(name_, what + " refers to missing accessor " + std::to_string(index));
    }
    const tinygltf::Accessor& accessor = model_.accessors[index];
    const std::string label = "accessor " + std::to_string(index) + " (" + what + ")";
    if (accessor.type != expectedType) {
      fail(name_, label + " has type " + typeName(accessor.type) + ", expected " + typeName(expectedType));
    }
    if (componentSize(accessor.componentType) == 0) fail(name_, label + " has an unsupported component type");
    const bool normalized = allowNormalized && accessor.normalized;
    std::vector<double> values = readDense(accessor, normalized, label);
    if (accessor.sparse.isSparse) applySparse(accessor, normalized, label, values);
    return values;
  }

 private:
  Bytes bufferView(int index, const std::string& label) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.bufferViews.size()) {
      fail(name_, label + " refers to missing bufferView " + std::to_string(index));
    }
    const tinygltf::BufferView& view = model_.bufferViews[index];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size()) {
      fail(name_, "bufferView " + std::to_string(index) + " refers to missing buffer " +
                      std::to_string(view.buffer));
    }
    const std::vector<unsigned char>& buffer = model_.buffers[view.buffer].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
      fail(name_, "bufferView " + std::to_string(index) + " is out of bounds of buffer " +
                      std::to_string(view.buffer));
    }
    return {buffer.data() + view.byteOffset, view.byteLength};
  }

  std::vector<double> readDense(const tinygltf::Accessor& accessor, bool normalized,
                                const std::string& label) const {
    const int components = componentCount(accessor.type);
    const std::size_t size = componentSize(accessor.componentType);
    const uint64_t elementSize = size * components;
    const uint64_t count = accessor.count;
    if (accessor.bufferView < 0) {
      if (count > kMaxUnbackedAccessorCount) fail(name_, label + " has no bufferView and a too large count");
      return std::vector<double>(static_cast<std::size_t>(count) * components, 0.0);
    }
    const Bytes bytes = bufferView(accessor.bufferView, label);
    const uint64_t declaredStride = model_.bufferViews[accessor.bufferView].byteStride;
    const uint64_t stride = declaredStride > 0 ? declaredStride : elementSize;
    if (!fits(accessor.byteOffset, count, stride, elementSize, bytes.size)) {
      fail(name_, label + " is out of bounds of its bufferView");
    }
    // count <= bytes.size / elementSize here (or stride overlaps elements), so this allocation is bounded.
    std::vector<double> values(static_cast<std::size_t>(count) * components);
    const uint8_t* element = bytes.data + accessor.byteOffset;
    for (std::size_t i = 0; i < count; ++i, element += stride) {
      for (int c = 0; c < components; ++c) {
        values[i * components + c] = readComponent(element + c * size, accessor.componentType, normalized);
      }
    }
    return values;
  }

  void applySparse(const tinygltf::Accessor& accessor, bool normalized, const std::string& label,
                   std::vector<double>& values) const {
    const auto& sparse = accessor.sparse;
    const int components = componentCount(accessor.type);
    const std::size_t size = componentSize(accessor.componentType);
    const uint64_t elementSize = size * components;
    if (sparse.count < 0 || static_cast<uint64_t>(sparse.count) > accessor.count) {
      fail(name_, label + " has an invalid sparse count");
    }
    const int indexType = sparse.indices.componentType;
    const std::size_t indexSize = componentSize(indexType);
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      fail(name_, label + " has an invalid sparse index type");
    }
    const Bytes indices = bufferView(sparse.indices.bufferView, label + " sparse indices");
    const Bytes substitutes = bufferView(sparse.values.bufferView, label + " sparse values");
    const uint64_t count = static_cast<uint64_t>(sparse.count);
    if (sparse.indices.byteOffset < 0 ||
        !fits(sparse.indices.byteOffset, count, indexSize, indexSize, indices.size) ||
        sparse.values.byteOffset < 0 ||
        !fits(sparse.values.byteOffset, count, elementSize, elementSize, substitutes.size)) {
      fail(name_, label + " sparse data is out of bounds of its bufferView");
    }
    for (uint64_t i = 0; i < count; ++i) {
      const auto target = static_cast<uint64_t>(
          readComponent(indices.data + sparse.indices.byteOffset + i * indexSize, indexType, false));
      if (target >= accessor.count) fail(name_, label + " has a sparse index out of range");
      const uint8_t* element = substitutes.data + sparse.values.byteOffset + i * elementSize;
      for (int c = 0; c < components; ++c) {
        values[target * components + c] =
            readComponent(element + c * size, accessor.componentType, normalized);
      }
    }
  }

  const tinygltf::Model& model_;
  const std::string& name_;
};

// ---- Primitives and welding ----------------------------------------------------------------------------

// Every source vertex of every triangle primitive, before welding.
struct SourceGeometry {
  std::vector<double> positions;  // transformed
  std::vector<float> uvs;
  bool allHaveUVs = true;
  std::vector<int32_t> triangles;  // source vertex indices
  int trianglePrimitives = 0;
};

bool isIdentity(const Mat4& m) {
  return m == kIdentity;
}

void appendPositions(const std::vector<double>& local, const Mat4& m, std::vector<double>& out) {
  if (isIdentity(m)) {
    // Skipping the arithmetic keeps coordinates bit-exact, and an inf coordinate from turning its
    // neighbours into 0 * inf = NaN.
    out.insert(out.end(), local.begin(), local.end());
    return;
  }
  for (std::size_t i = 0; i + 2 < local.size(); i += 3) {
    for (int row = 0; row < 3; ++row) {
      out.push_back(m[row] * local[i] + m[4 + row] * local[i + 1] + m[8 + row] * local[i + 2] + m[12 + row]);
    }
  }
}

// The corner list of a primitive as triangles, following the glTF spec for strips and fans.
void appendTriangles(const std::vector<uint32_t>& corners, int mode, int32_t base, const std::string& label,
                     const std::string& name, std::vector<int32_t>& out) {
  const std::size_t n = corners.size();
  const auto emit = [&](std::size_t a, std::size_t b, std::size_t c) {
    out.push_back(base + static_cast<int32_t>(corners[a]));
    out.push_back(base + static_cast<int32_t>(corners[b]));
    out.push_back(base + static_cast<int32_t>(corners[c]));
  };
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0) fail(name, label + " has " + std::to_string(n) + " indices, not a multiple of 3");
    for (std::size_t i = 0; i < n; i += 3) emit(i, i + 1, i + 2);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 0; i + 2 < n; ++i) emit(i, i + 1 + i % 2, i + 2 - i % 2);
  } else {
    for (std::size_t i = 0; i + 2 < n; ++i) emit(i + 1, i + 2, 0);
  }
}

std::vector<uint32_t> primitiveCorners(const AccessorReader& reader, const tinygltf::Model& model,
                                       const tinygltf::Primitive& primitive, std::size_t vertexCount,
                                       const std::string& label, const std::string& name) {
  std::vector<uint32_t> corners;
  if (primitive.indices < 0) {
    corners.resize(vertexCount);
    std::iota(corners.begin(), corners.end(), 0u);
    return corners;
  }
  if (static_cast<std::size_t>(primitive.indices) < model.accessors.size()) {
    const int type = model.accessors[primitive.indices].componentType;
    if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      fail(name, label + " indices have an invalid component type");
    }
  }
  const std::vector<double> indices =
      reader.read(primitive.indices, TINYGLTF_TYPE_SCALAR, false, label + " indices");
  corners.reserve(indices.size());
  for (double index : indices) {
    if (index >= static_cast<double>(vertexCount)) {
      fail(name, label + " has index " + std::to_string(static_cast<uint64_t>(index)) + " out of range (" +
                     std::to_string(vertexCount) + " vertices)");
    }
    corners.push_back(static_cast<uint32_t>(index));
  }
  return corners;
}

void appendPrimitive(const AccessorReader& reader, const tinygltf::Model& model,
                     const tinygltf::Primitive& primitive, const Mat4& transform, const std::string& label,
                     const std::string& name, SourceGeometry& geometry) {
  const auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) fail(name, label + " has no POSITION attribute");
  const std::vector<double> local =
      reader.read(position->second, TINYGLTF_TYPE_VEC3, true, label + " POSITION");
  const std::size_t vertexCount = local.size() / 3;
  const std::size_t base = geometry.positions.size() / 3;
  checkVertexCount(uint64_t{base} + vertexCount, name);

  const auto texcoord = primitive.attributes.find("TEXCOORD_0");
  if (texcoord == primitive.attributes.end()) {
    geometry.allHaveUVs = false;
    geometry.uvs = {};
  } else if (geometry.allHaveUVs) {
    const std::vector<double> uvs =
        reader.read(texcoord->second, TINYGLTF_TYPE_VEC2, true, label + " TEXCOORD_0");
    if (uvs.size() != local.size() / 3 * 2) fail(name, label + " TEXCOORD_0 and POSITION counts differ");
    for (double value : uvs) geometry.uvs.push_back(static_cast<float>(value));
  }

  const std::vector<uint32_t> corners = primitiveCorners(reader, model, primitive, vertexCount, label, name);
  appendPositions(local, transform, geometry.positions);
  appendTriangles(corners, primitive.mode, static_cast<int32_t>(base), label, name, geometry.triangles);
  ++geometry.trianglePrimitives;
}

SourceGeometry collectGeometry(const tinygltf::Model& model, const std::string& name) {
  SourceGeometry geometry;
  const AccessorReader reader(model, name);
  for (const MeshInstance& instance : sceneInstances(model, name)) {
    const auto& primitives = model.meshes[instance.mesh].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const int mode = primitives[p].mode;
      const std::string label = "mesh " + std::to_string(instance.mesh) + " primitive " + std::to_string(p);
      if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) continue;  // no surface
      if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
        fail(name, label + " has invalid mode " + std::to_string(mode));
      }
      appendPrimitive(reader, model, primitives[p], instance.transform, label, name, geometry);
    }
  }
  if (geometry.trianglePrimitives == 0) fail(name, "no triangle primitives in the scene");
  if (geometry.triangles.empty()) fail(name, "no triangles in the scene");
  return geometry;
}

struct PositionKey {
  uint64_t bits[3];
  bool operator==(const PositionKey& other) const { return std::equal(bits, bits + 3, other.bits); }
};

PositionKey keyOf(const double* p) {
  PositionKey key;
  for (int i = 0; i < 3; ++i) {
    const double value = p[i] == 0.0 ? 0.0 : p[i];  // -0 and +0 are the same place
    std::memcpy(&key.bits[i], &value, sizeof value);
  }
  return key;
}

// splitmix64's finalizer: coordinates converted from float have 29 zero low bits, so a weak mix would pile
// them into a few slots.
uint64_t mix(uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

uint64_t hashOf(const PositionKey& key) {
  return mix(mix(mix(key.bits[0]) ^ key.bits[1]) ^ key.bits[2]);
}

// Open addressing over welded vertex ids: several times faster than std::unordered_map on million-vertex
// meshes, which allocates a node per vertex.
class PositionTable {
 public:
  explicit PositionTable(std::size_t expected) {
    std::size_t capacity = 16;
    while (capacity < expected * 2) capacity *= 2;
    slots_.assign(capacity, -1);
    keys_.reserve(expected);
  }

  // The id of the key, inserting it with the next id when new.
  int32_t findOrInsert(const PositionKey& key, bool& inserted) {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t slot = static_cast<std::size_t>(hashOf(key)) & mask;; slot = (slot + 1) & mask) {
      if (slots_[slot] < 0) {
        slots_[slot] = static_cast<int32_t>(keys_.size());
        keys_.push_back(key);
        inserted = true;
        return slots_[slot];
      }
      if (keys_[slots_[slot]] == key) {
        inserted = false;
        return slots_[slot];
      }
    }
  }

 private:
  std::vector<int32_t> slots_;  // -1 = empty; never more than half full
  std::vector<PositionKey> keys_;
};

// glTF splits vertices at UV seams and normal creases; the field needs the connected surface, so vertices at
// exactly the same position become one, numbered in order of first appearance.
SurfaceMesh weld(const SourceGeometry& geometry) {
  SurfaceMesh mesh;
  const std::size_t sourceCount = geometry.positions.size() / 3;
  PositionTable table(sourceCount);
  mesh.sourceToWelded.reserve(sourceCount);
  for (std::size_t s = 0; s < sourceCount; ++s) {
    const double* p = &geometry.positions[s * 3];
    bool inserted = false;
    mesh.sourceToWelded.push_back(table.findOrInsert(keyOf(p), inserted));
    if (inserted) mesh.positions.insert(mesh.positions.end(), p, p + 3);
  }
  mesh.triangles.reserve(geometry.triangles.size());
  for (int32_t source : geometry.triangles) mesh.triangles.push_back(mesh.sourceToWelded[source]);
  if (geometry.allHaveUVs) {
    mesh.cornerUVs.reserve(geometry.triangles.size() * 2);
    for (int32_t source : geometry.triangles) {
      mesh.cornerUVs.push_back(geometry.uvs[source * 2]);
      mesh.cornerUVs.push_back(geometry.uvs[source * 2 + 1]);
    }
  }
  return mesh;
}

}  // namespace

SurfaceMesh loadGltf(const uint8_t* data, std::size_t size, bool binary, const std::string& baseDir,
                     const std::string& name) {
  const tinygltf::Model model = parseModel(data, size, binary, baseDir, name);
  try {
    return weld(collectGeometry(model, name));
  } catch (const std::bad_alloc&) {
    fail(name, "glTF too large to load (out of memory)");
  }
}

}  // namespace tvf::io_detail

namespace tvf {

GltfSource loadGltfSource(const uint8_t* data, std::size_t size, bool binary, const std::string& baseDir,
                          const std::string& name) {
  using namespace io_detail;
  const tinygltf::Model model = parseModel(data, size, binary, baseDir, name);
  GltfSource source;
  uint32_t glbLength = 0;
  const std::string_view json = binary ? checkGlbContainer(data, size, name, glbLength)
                                       : std::string_view(reinterpret_cast<const char*>(data), size);
  source.document = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (source.document.is_discarded() || !source.document.is_object()) fail(name, "invalid glTF JSON");
  for (const tinygltf::Buffer& buffer : model.buffers) source.buffers.emplace_back(buffer.data);
  // The same walk as collectGeometry: instances in scene order, surface primitives only.
  const AccessorReader reader(model, name);
  for (const MeshInstance& instance : sceneInstances(model, name)) {
    const auto& primitives = model.meshes[instance.mesh].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      if (primitives[p].mode < TINYGLTF_MODE_TRIANGLES) continue;
      const int position = primitives[p].attributes.at("POSITION");
      GltfPrimitiveInstance entry;
      entry.mesh = instance.mesh;
      entry.primitive = static_cast<int>(p);
      entry.vertexCount = static_cast<uint32_t>(model.accessors.at(position).count);
      entry.transform = instance.transform;
      const std::string label = "mesh " + std::to_string(instance.mesh) + " primitive " + std::to_string(p);
      std::vector<int32_t> triangles;
      appendTriangles(primitiveCorners(reader, model, primitives[p], entry.vertexCount, label, name),
                      primitives[p].mode, 0, label, name, triangles);
      entry.corners.assign(triangles.begin(), triangles.end());
      source.primitives.push_back(std::move(entry));
    }
  }
  return source;
}

}  // namespace tvf
