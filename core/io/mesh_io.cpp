#include "io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>

#if __has_include(<fast_float/fast_float.h>)
#include <fast_float/fast_float.h>
#endif

#include "io/loaders.h"

namespace tvf {
namespace io_detail {

void fail(const std::string& name, const std::string& problem) {
  throw InputError(name + ": " + problem);
}

void failAtLine(const std::string& name, std::size_t line, const std::string& problem) {
  throw InputError(name + ":" + std::to_string(line) + ": " + problem);
}

std::string quoteToken(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  if (token.size() <= kMaxShown) return "'" + std::string(token) + "'";
  return "'" + std::string(token.substr(0, kMaxShown)) + "...'";
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= size_) return false;
  const char* start = begin_ + pos_;
  const void* newline = std::memchr(start, '\n', size_ - pos_);
  std::size_t length =
      newline ? static_cast<std::size_t>(static_cast<const char*>(newline) - start) : size_ - pos_;
  pos_ += newline ? length + 1 : length;
  if (length > 0 && start[length - 1] == '\r') --length;
  line = std::string_view(start, length);
  ++line_;
  return true;
}

bool Tokenizer::next(std::string_view& token) {
  std::size_t begin = 0;
  while (begin < rest_.size() && isSpace(rest_[begin])) ++begin;
  if (begin == rest_.size()) {
    rest_ = {};
    return false;
  }
  std::size_t end = begin;
  while (end < rest_.size() && !isSpace(rest_[end])) ++end;
  token = rest_.substr(begin, end - begin);
  rest_ = rest_.substr(end);
  return true;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  return text;
}

std::string_view stripComment(std::string_view line) {
  const std::size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

bool parseDouble(std::string_view token, double& value) {
  // from_chars rejects a leading '+', which some exporters write.
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  if (token.empty()) return false;
#if __has_include(<fast_float/fast_float.h>)
  // Exact and locale-independent like from_chars, and fast where the standard library has no floating-point
  // from_chars (emscripten's libc++, whose strtod goes through software long double: bunny00.off loads
  // 50-130 ms faster in wasm).
  // Overflow gives +-inf and underflow the denormal or zero, numbers all the same.
  const auto result = fast_float::from_chars(token.data(), token.data() + token.size(), value);
  return result.ec == std::errc() && result.ptr == token.data() + token.size();
#elif defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  // from_chars ignores the locale, unlike strtod, so "1.5" never turns into 1 under a German LC_NUMERIC.
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  if (result.ec == std::errc::result_out_of_range) {
    // Overflow and underflow are numbers all the same; let strtod pick +-inf or the denormal/zero.
    const std::string copy(token);
    value = std::strtod(copy.c_str(), nullptr);
    return result.ptr == token.data() + token.size();
  }
  return result.ec == std::errc() && result.ptr == token.data() + token.size();
#else
  // Standard libraries without floating-point from_chars (older libc++, e.g. emscripten's).
  const std::string copy(token);
  char* end = nullptr;
  value = std::strtod(copy.c_str(), &end);
  return end == copy.c_str() + copy.size();
#endif
}

bool parseInteger(std::string_view token, int64_t& value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  if (result.ptr != token.data() + token.size() || token.empty()) return false;
  if (result.ec == std::errc::result_out_of_range) {
    value = token[0] == '-' ? std::numeric_limits<int64_t>::min() : std::numeric_limits<int64_t>::max();
    return true;
  }
  return result.ec == std::errc();
}

int32_t toIndex(int64_t value) {
  if (value < std::numeric_limits<int32_t>::min() || value > std::numeric_limits<int32_t>::max()) return -1;
  return static_cast<int32_t>(value);
}

void appendFan(const std::vector<int32_t>& polygon, std::vector<int32_t>& triangles) {
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    triangles.push_back(polygon[0]);
    triangles.push_back(polygon[i]);
    triangles.push_back(polygon[i + 1]);
  }
}

void checkVertexCount(uint64_t vertexCount, const std::string& name) {
  if (vertexCount > static_cast<uint64_t>(std::numeric_limits<int32_t>::max())) {
    fail(name, "too many vertices (" + std::to_string(vertexCount) + ")");
  }
}

}  // namespace io_detail

namespace {

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string displayName(MeshFormat format) {
  switch (format) {
    case MeshFormat::Gltf:
    case MeshFormat::Glb:
      return "glTF data";
    case MeshFormat::Off:
      return "OFF data";
    case MeshFormat::Obj:
      return "OBJ data";
    case MeshFormat::Ply:
      return "PLY data";
  }
  return "mesh data";
}

SurfaceMesh loadBytes(const uint8_t* data, std::size_t size, MeshFormat format, const std::string& baseDir,
                      const std::string& name) {
  if (size == 0) io_detail::fail(name, "empty file");
  switch (format) {
    case MeshFormat::Gltf:
      return io_detail::loadGltf(data, size, false, baseDir, name);
    case MeshFormat::Glb:
      return io_detail::loadGltf(data, size, true, baseDir, name);
    case MeshFormat::Off:
      return io_detail::loadOff(data, size, name);
    case MeshFormat::Obj:
      return io_detail::loadObj(data, size, name);
    case MeshFormat::Ply:
      return io_detail::loadPly(data, size, name);
  }
  io_detail::fail(name, "unknown mesh format");
}

std::vector<uint8_t> readFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) io_detail::fail(path, "file not found");
  if (!fs::is_regular_file(status)) io_detail::fail(path, "not a regular file, cannot be read");
  std::ifstream in(path, std::ios::binary);
  if (!in) io_detail::fail(path, "file cannot be opened for reading");
  // One bulk read: going through istreambuf_iterator costs a call per byte on files of hundreds of MB.
  std::vector<uint8_t> bytes;
  const auto expectedSize = fs::file_size(path, ec);
  if (!ec) bytes.reserve(static_cast<std::size_t>(expectedSize));
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0)
    bytes.insert(bytes.end(), chunk, chunk + in.gcount());
  if (in.bad()) io_detail::fail(path, "read error, file is unreadable");
  return bytes;
}

std::string parentDirectory(const std::string& path) {
  const std::string parent = std::filesystem::path(path).parent_path().string();
  return parent.empty() ? "." : parent;
}

}  // namespace

MeshFormat formatFromPath(const std::string& path) {
  const std::string fileName = std::filesystem::path(path).filename().string();
  const std::size_t dot = fileName.rfind('.');
  const std::string extension = dot == std::string::npos ? "" : lowercase(fileName.substr(dot + 1));
  if (extension == "gltf") return MeshFormat::Gltf;
  if (extension == "glb") return MeshFormat::Glb;
  if (extension == "off") return MeshFormat::Off;
  if (extension == "obj") return MeshFormat::Obj;
  if (extension == "ply") return MeshFormat::Ply;
  const std::string problem = extension.empty()
                                  ? "no file extension"
                                  : "unknown file extension " + io_detail::quoteToken("." + extension);
  io_detail::fail(path, problem + " (expected .gltf, .glb, .off, .obj or .ply)");
}

MeshFormat formatFromBytes(const uint8_t* data, std::size_t size) {
  const auto startsWith = [&](std::size_t offset, std::string_view prefix) {
    return size >= offset + prefix.size() && std::equal(prefix.begin(), prefix.end(), data + offset);
  };
  if (startsWith(0, "glTF")) return MeshFormat::Glb;
  std::size_t first = 0;
  // Skip a UTF-8 byte order mark, which some text editors put in front of JSON and OBJ files.
  if (startsWith(0, "\xEF\xBB\xBF")) first = 3;
  while (first < size && io_detail::isSpace(static_cast<char>(data[first]))) ++first;
  if (startsWith(first, "{")) return MeshFormat::Gltf;
  if (startsWith(first, "ply")) return MeshFormat::Ply;
  for (std::string_view keyword : {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCOFF", "STNOFF", "STCNOFF"}) {
    if (startsWith(first, keyword)) return MeshFormat::Off;
  }
  return MeshFormat::Obj;
}

SurfaceMesh loadMesh(const std::string& path) {
  const MeshFormat format = formatFromPath(path);
  const std::vector<uint8_t> bytes = readFile(path);
  return loadBytes(bytes.data(), bytes.size(), format, parentDirectory(path), path);
}

SurfaceMesh loadMeshFromMemory(const uint8_t* data, std::size_t size, MeshFormat format,
                               const std::string& baseDir) {
  return loadBytes(data, size, format, baseDir, displayName(format));
}

}  // namespace tvf
