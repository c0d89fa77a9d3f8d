#pragma once
// Internal to core/io: the per-format loaders behind mesh_io.h and the text helpers they share. Every loader
// takes the raw bytes plus a display name (the file path, or "OBJ data" etc. for in-memory input) that
// prefixes each error message.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/surface_mesh.h"

namespace tvf::io_detail {

SurfaceMesh loadGltf(const uint8_t* data, std::size_t size, bool binary, const std::string& baseDir,
                     const std::string& name);
SurfaceMesh loadOff(const uint8_t* data, std::size_t size, const std::string& name);
SurfaceMesh loadObj(const uint8_t* data, std::size_t size, const std::string& name);
SurfaceMesh loadPly(const uint8_t* data, std::size_t size, const std::string& name);

[[noreturn]] void fail(const std::string& name, const std::string& problem);

// glTF accessors (gltf_loader.cpp; the export's vertex split reads them too): a component type's size in
// bytes (0: not one glTF has), one component read little-endian (normalized integers mapped to [-1, 1] or [0,
// 1]), and whether `count` elements of `elementSize` bytes, `stride` apart, fit in `available` bytes after
// `offset`.
std::size_t componentSize(int componentType);
double readComponent(const uint8_t* p, int componentType, bool normalized);
bool fits(uint64_t offset, uint64_t count, uint64_t stride, uint64_t elementSize, uint64_t available);
[[noreturn]] void failAtLine(const std::string& name, std::size_t line, const std::string& problem);

// A token for an error message; long tokens are cut so a hostile file cannot produce a huge message.
std::string quoteToken(std::string_view token);

// Splits bytes into lines (without the "\n" or "\r\n"), counting them from 1.
class LineReader {
 public:
  LineReader(const uint8_t* data, std::size_t size)
      : begin_(reinterpret_cast<const char*>(data)), size_(size) {}
  bool next(std::string_view& line);
  std::size_t lineNumber() const { return line_; }
  // Byte offset just past the line returned last.
  std::size_t offset() const { return pos_; }

 private:
  const char* begin_;
  std::size_t size_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

// Splits one line into whitespace-separated tokens.
class Tokenizer {
 public:
  explicit Tokenizer(std::string_view text) : rest_(text) {}
  bool next(std::string_view& token);

 private:
  std::string_view rest_;
};

inline bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}
std::string_view trim(std::string_view text);
// Cuts a '#' comment off a line.
std::string_view stripComment(std::string_view line);

// Whole-token parses; nan and inf are accepted as numbers (the mesh checks report them).
bool parseDouble(std::string_view token, double& value);
bool parseInteger(std::string_view token, int64_t& value);
// Vertex indices that do not fit int32 become -1: still out of range, so the topology checks report them.
int32_t toIndex(int64_t value);

// Appends the fan (p0, pi, pi+1) of a polygon given as its corner indices.
void appendFan(const std::vector<int32_t>& polygon, std::vector<int32_t>& triangles);

// Throws when the vertex count would not fit SurfaceMesh's int32 indices.
void checkVertexCount(uint64_t vertexCount, const std::string& name);

}  // namespace tvf::io_detail
