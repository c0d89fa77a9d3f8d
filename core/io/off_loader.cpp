// OFF: an optional "OFF" keyword, "numVertices numFaces [numEdges]", then one vertex and one face per line.
// Reading line by line (not token by token) lets us ignore the colors and normals that the COFF/NOFF
// variants and many exporters append to vertex and face lines.
#include <algorithm>

#include "io/loaders.h"

namespace tvf::io_detail {
namespace {

// The non-blank lines of the file with '#' comments removed.
class OffLines {
 public:
  OffLines(const uint8_t* data, std::size_t size, const std::string& name)
      : reader_(data, size), name_(name) {}

  bool next(std::string_view& line) {
    std::string_view raw;
    while (reader_.next(raw)) {
      line = trim(stripComment(raw));
      if (!line.empty()) return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& problem) const {
    failAtLine(name_, reader_.lineNumber(), problem);
  }

 private:
  LineReader reader_;
  const std::string& name_;
};

// [ST][C][N]OFF; the 4OFF / nOFF variants describe other dimensions than 3.
bool isOffKeyword(std::string_view token) {
  if (token.substr(0, 2) == "ST") token.remove_prefix(2);
  if (token.substr(0, 1) == "C") token.remove_prefix(1);
  if (token.substr(0, 1) == "N") token.remove_prefix(1);
  return token == "OFF";
}

bool looksLikeOffKeyword(std::string_view token) {
  return token.size() >= 3 && token.substr(token.size() - 3) == "OFF";
}

int64_t readCount(Tokenizer& tokens, const OffLines& lines, const char* what, bool required) {
  std::string_view token;
  if (!tokens.next(token)) {
    if (required) lines.fail(std::string("header lacks the number of ") + what);
    return 0;
  }
  int64_t count = 0;
  if (!parseInteger(token, count))
    lines.fail("number of " + std::string(what) + " " + quoteToken(token) + " is not an integer");
  if (count < 0) lines.fail("negative number of " + std::string(what));
  return count;
}

// The line that holds the counts: after the keyword on the same line, or the next line.
std::string_view countsLine(OffLines& lines, const std::string& name) {
  std::string_view line;
  if (!lines.next(line)) fail(name, "empty file");
  Tokenizer tokens(line);
  std::string_view first;
  tokens.next(first);
  if (isOffKeyword(first)) {
    const std::string_view rest = trim(line.substr(first.size()));
    if (rest.substr(0, 6) == "BINARY") lines.fail("binary OFF is not supported");
    if (!rest.empty()) return rest;
    if (!lines.next(line)) lines.fail("header lacks the vertex and face counts");
    return line;
  }
  if (looksLikeOffKeyword(first)) lines.fail("unsupported OFF variant " + quoteToken(first));
  int64_t ignored = 0;
  // The keyword is optional in OFF, so a file may start right with the counts.
  if (!parseInteger(first, ignored))
    lines.fail("not an OFF file: expected 'OFF', found " + quoteToken(first));
  return line;
}

void readVertices(OffLines& lines, int64_t count, std::vector<double>& positions) {
  std::string_view line;
  for (int64_t v = 0; v < count; ++v) {
    if (!lines.next(line)) {
      lines.fail("unexpected end of file: expected " + std::to_string(count) + " vertices, found " +
                 std::to_string(v));
    }
    Tokenizer tokens(line);
    for (int axis = 0; axis < 3; ++axis) {
      std::string_view token;
      if (!tokens.next(token)) lines.fail("vertex " + std::to_string(v) + " has fewer than 3 coordinates");
      double value = 0.0;
      if (!parseDouble(token, value)) lines.fail("coordinate " + quoteToken(token) + " is not a number");
      positions.push_back(value);
    }
  }
}

void readFaces(OffLines& lines, int64_t count, std::vector<int32_t>& triangles) {
  std::string_view line;
  std::vector<int32_t> polygon;
  for (int64_t f = 0; f < count; ++f) {
    if (!lines.next(line)) {
      lines.fail("unexpected end of file: expected " + std::to_string(count) + " faces, found " +
                 std::to_string(f));
    }
    Tokenizer tokens(line);
    std::string_view token;
    int64_t corners = 0;
    tokens.next(token);
    if (!parseInteger(token, corners))
      lines.fail("face vertex count " + quoteToken(token) + " is not an integer");
    if (corners < 3) lines.fail("face " + std::to_string(f) + " has fewer than 3 vertices");
    polygon.clear();
    for (int64_t c = 0; c < corners; ++c) {
      if (!tokens.next(token)) {
        lines.fail("face " + std::to_string(f) + " lists fewer than its " + std::to_string(corners) +
                   " vertices");
      }
      int64_t index = 0;
      if (!parseInteger(token, index)) lines.fail("vertex index " + quoteToken(token) + " is not an integer");
      polygon.push_back(toIndex(index));
    }
    appendFan(polygon, triangles);
  }
}

}  // namespace

SurfaceMesh loadOff(const uint8_t* data, std::size_t size, const std::string& name) {
  OffLines lines(data, size, name);
  Tokenizer counts(countsLine(lines, name));
  const int64_t numVertices = readCount(counts, lines, "vertices", true);
  const int64_t numFaces = readCount(counts, lines, "faces", true);
  checkVertexCount(static_cast<uint64_t>(numVertices), name);
  if (numFaces == 0) fail(name, "no faces");

  SurfaceMesh mesh;
  // Never trust a count for a reservation: a tiny file could claim billions of vertices.
  const auto plausible = static_cast<int64_t>(size / 4);
  mesh.positions.reserve(static_cast<std::size_t>(std::min(numVertices, plausible)) * 3);
  mesh.triangles.reserve(static_cast<std::size_t>(std::min(numFaces, plausible)) * 3);
  readVertices(lines, numVertices, mesh.positions);
  readFaces(lines, numFaces, mesh.triangles);
  return mesh;
}

}  // namespace tvf::io_detail
