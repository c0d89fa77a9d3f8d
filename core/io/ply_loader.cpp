// Stanford PLY in ascii, binary_little_endian and binary_big_endian. Only vertex x/y/z and the face index
// list are kept; every other property and element is still read through (lists have variable length), which
// is the only way to find where the next value starts.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "io/loaders.h"

namespace tvf::io_detail {
namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };
// What a property means to us; everything but the roles we need is skipped.
enum class Role { Skip, X, Y, Z, FaceIndices };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // the element type for lists
  bool isList = false;
  PlyType countType = PlyType::UInt8;
  Role role = Role::Skip;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::Ascii;
  std::vector<PlyElement> elements;
  std::size_t bodyOffset = 0;
  std::size_t bodyLine = 0;  // line number of the first body line, for ascii errors
};

bool parseType(std::string_view name, PlyType& type) {
  static const std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& entry : kNames) {
    if (entry.first == name) {
      type = entry.second;
      return true;
    }
  }
  return false;
}

std::size_t typeSize(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

class HeaderParser {
 public:
  HeaderParser(const uint8_t* data, std::size_t size, const std::string& name)
      : lines_(data, size), name_(name) {}

  PlyHeader parse() {
    std::string_view line;
    if (!lines_.next(line) || trim(line) != "ply") fail(name_, "not a PLY file (missing 'ply' magic line)");
    bool sawFormat = false;
    while (lines_.next(line)) {
      Tokenizer tokens(line);
      std::string_view keyword;
      if (!tokens.next(keyword)) continue;
      if (keyword == "end_header") {
        if (!sawFormat) failHere("header has no format line");
        header_.bodyOffset = lines_.offset();
        header_.bodyLine = lines_.lineNumber() + 1;
        return std::move(header_);
      }
      if (keyword == "format") {
        parseFormat(tokens);
        sawFormat = true;
      } else if (keyword == "element") {
        parseElement(tokens);
      } else if (keyword == "property") {
        parseProperty(tokens);
      } else if (keyword != "comment" && keyword != "obj_info") {
        failHere("unknown header keyword " + quoteToken(keyword));
      }
    }
    fail(name_, "truncated header (no end_header line)");
  }

 private:
  [[noreturn]] void failHere(const std::string& problem) const {
    failAtLine(name_, lines_.lineNumber(), problem);
  }

  std::string_view word(Tokenizer& tokens, const char* what) const {
    std::string_view token;
    if (!tokens.next(token)) failHere(std::string("missing ") + what);
    return token;
  }

  PlyType type(Tokenizer& tokens) const {
    const std::string_view token = word(tokens, "property type");
    PlyType result;
    if (!parseType(token, result)) failHere("unknown property type " + quoteToken(token));
    return result;
  }

  void parseFormat(Tokenizer& tokens) {
    const std::string_view encoding = word(tokens, "format encoding");
    if (encoding == "ascii") {
      header_.encoding = PlyEncoding::Ascii;
    } else if (encoding == "binary_little_endian") {
      header_.encoding = PlyEncoding::BinaryLittleEndian;
    } else if (encoding == "binary_big_endian") {
      header_.encoding = PlyEncoding::BinaryBigEndian;
    } else {
      failHere("unknown format " + quoteToken(encoding));
    }
  }

  void parseElement(Tokenizer& tokens) {
    PlyElement element;
    element.name = std::string(word(tokens, "element name"));
    const std::string_view countText = word(tokens, "element count");
    int64_t count = 0;
    if (!parseInteger(countText, count))
      failHere("element count " + quoteToken(countText) + " is not an integer");
    if (count < 0) failHere("negative element count");
    element.count = static_cast<uint64_t>(count);
    header_.elements.push_back(std::move(element));
  }

  void parseProperty(Tokenizer& tokens) {
    if (header_.elements.empty()) failHere("property before any element");
    PlyProperty property;
    std::string_view token;
    if (tokens.next(token) && token == "list") {
      property.isList = true;
      property.countType = type(tokens);
      property.type = type(tokens);
    } else {
      Tokenizer again(token);  // the token was the scalar type
      property.type = type(again);
    }
    property.name = std::string(word(tokens, "property name"));
    header_.elements.back().properties.push_back(std::move(property));
  }

  LineReader lines_;
  const std::string& name_;
  PlyHeader header_;
};

// Assigns roles and checks up front that the file has what we need, so these errors come before any
// body parsing error.
void assignRoles(PlyHeader& header, const std::string& name) {
  PlyElement* vertices = nullptr;
  PlyElement* faces = nullptr;
  for (PlyElement& element : header.elements) {
    if (element.name == "vertex" && !vertices) vertices = &element;
    if (element.name == "face" && !faces) faces = &element;
  }
  if (!vertices) fail(name, "no vertex element");
  checkVertexCount(vertices->count, name);
  const std::pair<const char*, Role> axes[] = {{"x", Role::X}, {"y", Role::Y}, {"z", Role::Z}};
  for (const auto& axis : axes) {
    auto it = std::find_if(vertices->properties.begin(), vertices->properties.end(),
                           [&](const PlyProperty& p) { return p.name == axis.first && !p.isList; });
    if (it == vertices->properties.end()) {
      fail(name, std::string("vertex element has no '") + axis.first + "' property");
    }
    it->role = axis.second;
  }
  if (!faces || faces->count == 0) fail(name, "no faces");
  auto list = std::find_if(faces->properties.begin(), faces->properties.end(), [](const PlyProperty& p) {
    return p.isList && (p.name == "vertex_indices" || p.name == "vertex_index");
  });
  if (list == faces->properties.end()) fail(name, "face element has no 'vertex_indices' list");
  list->role = Role::FaceIndices;
}

// Values of an ascii body: whitespace-separated tokens, tracked by line for error messages.
class AsciiReader {
 public:
  AsciiReader(const uint8_t* data, std::size_t size, std::size_t firstLine, const std::string& name)
      : data_(reinterpret_cast<const char*>(data)), size_(size), line_(firstLine), name_(name) {}

  double number(PlyType, const char* what) {
    const std::string_view token = next(what);
    double value = 0.0;
    if (!parseDouble(token, value))
      failHere(std::string(what) + " " + quoteToken(token) + " is not a number");
    return value;
  }
  int64_t integer(PlyType, const char* what) {
    const std::string_view token = next(what);
    int64_t value = 0;
    if (!parseInteger(token, value))
      failHere(std::string(what) + " " + quoteToken(token) + " is not an integer");
    return value;
  }
  void skip(PlyType) { next("property value"); }
  [[noreturn]] void failHere(const std::string& problem) const { failAtLine(name_, line_, problem); }

 private:
  std::string_view next(const char* what) {
    while (pos_ < size_ && isSpace(data_[pos_])) {
      if (data_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ == size_) failHere(std::string("unexpected end of file while reading ") + what);
    const std::size_t begin = pos_;
    while (pos_ < size_ && !isSpace(data_[pos_])) ++pos_;
    return std::string_view(data_ + begin, pos_ - begin);
  }

  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  std::size_t line_;
  const std::string& name_;
};

// Values of a binary body; every read checks the remaining size first.
class BinaryReader {
 public:
  BinaryReader(const uint8_t* data, std::size_t size, bool bigEndian, const std::string& name)
      : data_(data), size_(size), bigEndian_(bigEndian), name_(name) {}

  double number(PlyType type, const char* what) {
    const uint64_t bits = read(typeSize(type), what);
    switch (type) {
      case PlyType::Int8:
        return static_cast<int8_t>(static_cast<uint8_t>(bits));
      case PlyType::UInt8:
        return static_cast<uint8_t>(bits);
      case PlyType::Int16:
        return static_cast<int16_t>(static_cast<uint16_t>(bits));
      case PlyType::UInt16:
        return static_cast<uint16_t>(bits);
      case PlyType::Int32:
        return static_cast<int32_t>(static_cast<uint32_t>(bits));
      case PlyType::UInt32:
        return static_cast<uint32_t>(bits);
      case PlyType::Float32: {
        const auto narrow = static_cast<uint32_t>(bits);
        float value;
        std::memcpy(&value, &narrow, sizeof value);
        return value;
      }
      case PlyType::Float64: {
        double value;
        std::memcpy(&value, &bits, sizeof value);
        return value;
      }
    }
    return 0.0;
  }
  int64_t integer(PlyType type, const char* what) {
    const double value = number(type, what);
    // Every integer PLY type converts to double exactly; a float-typed list must still hold integers.
    if (!(std::floor(value) == value && std::fabs(value) < 9.0e15)) {
      failHere(std::string(what) + " " + std::to_string(value) + " is not an integer");
    }
    return static_cast<int64_t>(value);
  }
  void skip(PlyType type) { read(typeSize(type), "property value"); }
  [[noreturn]] void failHere(const std::string& problem) const {
    fail(name_, problem + " (binary data, byte " + std::to_string(pos_) + ")");
  }

 private:
  uint64_t read(std::size_t bytes, const char* what) {
    if (size_ - pos_ < bytes) failHere(std::string("truncated file: data ends while reading ") + what);
    uint64_t bits = 0;
    for (std::size_t i = 0; i < bytes; ++i) {
      const std::size_t shift = bigEndian_ ? bytes - 1 - i : i;
      bits |= static_cast<uint64_t>(data_[pos_ + i]) << (8 * shift);
    }
    pos_ += bytes;
    return bits;
  }

  const uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  bool bigEndian_;
  const std::string& name_;
};

template <class Reader>
int64_t listLength(Reader& reader, const PlyProperty& property) {
  const int64_t length = reader.integer(property.countType, "list length");
  if (length < 0) reader.failHere("negative list length");
  return length;
}

template <class Reader>
void skipProperty(Reader& reader, const PlyProperty& property) {
  if (!property.isList) return reader.skip(property.type);
  // Bounded by the data: each skip consumes a token or bytes and fails at the end of the file.
  for (int64_t i = listLength(reader, property); i > 0; --i) reader.skip(property.type);
}

template <class Reader>
void readVertices(Reader& reader, const PlyElement& element, std::vector<double>& positions) {
  double xyz[3] = {0.0, 0.0, 0.0};
  for (uint64_t v = 0; v < element.count; ++v) {
    for (const PlyProperty& property : element.properties) {
      if (property.role == Role::Skip) {
        skipProperty(reader, property);
      } else {
        xyz[static_cast<int>(property.role) - static_cast<int>(Role::X)] =
            reader.number(property.type, "coordinate");
      }
    }
    positions.insert(positions.end(), xyz, xyz + 3);
  }
}

template <class Reader>
void readFaces(Reader& reader, const PlyElement& element, std::vector<int32_t>& triangles) {
  std::vector<int32_t> polygon;
  for (uint64_t f = 0; f < element.count; ++f) {
    for (const PlyProperty& property : element.properties) {
      if (property.role != Role::FaceIndices) {
        skipProperty(reader, property);
        continue;
      }
      const int64_t corners = listLength(reader, property);
      if (corners < 3) reader.failHere("face " + std::to_string(f) + " has fewer than 3 vertices");
      polygon.clear();
      for (int64_t c = 0; c < corners; ++c)
        polygon.push_back(toIndex(reader.integer(property.type, "vertex index")));
      appendFan(polygon, triangles);
    }
  }
}

template <class Reader>
void readBody(Reader& reader, const PlyHeader& header, std::size_t bodySize, SurfaceMesh& mesh) {
  bool readVertexElement = false;
  bool readFaceElement = false;
  for (const PlyElement& element : header.elements) {
    // An element without properties occupies no bytes; looping over its (possibly huge) count would hang.
    if (element.properties.empty()) continue;
    if (element.name == "vertex" && !readVertexElement) {
      // Never reserve from a count alone: a tiny file can claim billions of vertices.
      mesh.positions.reserve(static_cast<std::size_t>(std::min<uint64_t>(element.count, bodySize)) * 3);
      readVertices(reader, element, mesh.positions);
      readVertexElement = true;
    } else if (element.name == "face" && !readFaceElement) {
      mesh.triangles.reserve(static_cast<std::size_t>(std::min<uint64_t>(element.count, bodySize)) * 3);
      readFaces(reader, element, mesh.triangles);
      readFaceElement = true;
    } else {
      for (uint64_t i = 0; i < element.count; ++i) {
        for (const PlyProperty& property : element.properties) skipProperty(reader, property);
      }
    }
  }
}

}  // namespace

SurfaceMesh loadPly(const uint8_t* data, std::size_t size, const std::string& name) {
  PlyHeader header = HeaderParser(data, size, name).parse();
  assignRoles(header, name);
  const uint8_t* body = data + header.bodyOffset;
  const std::size_t bodySize = size - header.bodyOffset;
  SurfaceMesh mesh;
  if (header.encoding == PlyEncoding::Ascii) {
    AsciiReader reader(body, bodySize, header.bodyLine, name);
    readBody(reader, header, bodySize, mesh);
  } else {
    BinaryReader reader(body, bodySize, header.encoding == PlyEncoding::BinaryBigEndian, name);
    readBody(reader, header, bodySize, mesh);
  }
  return mesh;
}

}  // namespace tvf::io_detail
