// Wavefront OBJ: only v, vt and f matter for a surface; every other statement (vn, o, g, s, usemtl, l, ...)
// is skipped.
#include "io/loaders.h"

namespace tvf::io_detail {
namespace {

struct Corner {
  int32_t vertex = -1;
  bool hasUV = false;
  int64_t uv = 0;  // resolved 0-based index into the vt list
};

// 1-based, or negative counting back from the last element read so far. 0 is invalid in OBJ; it becomes -1
// so that the topology checks report it like any other out-of-range index.
int64_t resolveIndex(int64_t index, int64_t count) {
  if (index > 0) return index - 1;
  if (index < 0) return count + index;
  return -1;
}

class ObjParser {
 public:
  explicit ObjParser(const std::string& name) : name_(name) {}

  void parseLine(std::string_view line, std::size_t lineNumber) {
    line_ = lineNumber;
    Tokenizer tokens(stripComment(line));
    std::string_view keyword;
    if (!tokens.next(keyword)) return;
    sawStatement_ = true;
    if (keyword == "v") {
      parseVertex(tokens);
    } else if (keyword == "vt") {
      parseTexcoord(tokens);
    } else if (keyword == "f" || keyword == "fo") {
      parseFace(tokens);
    }
  }

  SurfaceMesh finish() {
    if (!sawStatement_) fail(name_, "empty file");
    if (mesh_.triangles.empty()) fail(name_, "no faces");
    checkVertexCount(mesh_.positions.size() / 3, name_);
    if (!allCornersHaveUV_) mesh_.cornerUVs.clear();
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void failHere(const std::string& problem) const { failAtLine(name_, line_, problem); }

  double readNumber(Tokenizer& tokens, const char* what) {
    std::string_view token;
    if (!tokens.next(token)) failHere(std::string("missing ") + what);
    double value = 0.0;
    if (!parseDouble(token, value))
      failHere(std::string(what) + " " + quoteToken(token) + " is not a number");
    return value;
  }

  void parseVertex(Tokenizer& tokens) {
    for (const char* axis : {"x coordinate", "y coordinate", "z coordinate"}) {
      mesh_.positions.push_back(readNumber(tokens, axis));
    }
  }

  void parseTexcoord(Tokenizer& tokens) {
    const double u = readNumber(tokens, "texture coordinate u");
    std::string_view token;
    double v = 0.0;  // v is optional in OBJ
    if (tokens.next(token) && !parseDouble(token, v)) {
      failHere("texture coordinate v " + quoteToken(token) + " is not a number");
    }
    texcoords_.push_back(static_cast<float>(u));
    texcoords_.push_back(static_cast<float>(v));
  }

  int64_t readIndex(std::string_view text, std::string_view corner) const {
    int64_t index = 0;
    if (!parseInteger(text, index)) failHere("face index " + quoteToken(corner) + " is not an integer");
    return index;
  }

  // "v", "v/vt", "v/vt/vn" or "v//vn".
  Corner parseCorner(std::string_view token) const {
    std::string_view parts[3];
    std::size_t numParts = 0;
    std::string_view rest = token;
    while (true) {
      const std::size_t slash = rest.find('/');
      if (numParts == 3) failHere("malformed face corner " + quoteToken(token));
      parts[numParts++] = rest.substr(0, slash);
      if (slash == std::string_view::npos) break;
      rest = rest.substr(slash + 1);
    }
    Corner corner;
    const auto numVertices = static_cast<int64_t>(mesh_.positions.size() / 3);
    corner.vertex = toIndex(resolveIndex(readIndex(parts[0], token), numVertices));
    if (numParts > 1 && !parts[1].empty()) {
      corner.hasUV = true;
      corner.uv = resolveIndex(readIndex(parts[1], token), static_cast<int64_t>(texcoords_.size() / 2));
      if (corner.uv < 0 || corner.uv >= static_cast<int64_t>(texcoords_.size() / 2)) {
        failHere("texture coordinate index in " + quoteToken(token) + " is out of range");
      }
    }
    if (numParts > 2 && !parts[2].empty())
      readIndex(parts[2], token);  // normals are unused but must be valid
    return corner;
  }

  void parseFace(Tokenizer& tokens) {
    corners_.clear();
    std::string_view token;
    while (tokens.next(token)) corners_.push_back(parseCorner(token));
    if (corners_.size() < 3) failHere("face with fewer than 3 vertices");
    polygon_.clear();
    bool faceHasUVs = true;
    for (const Corner& corner : corners_) {
      polygon_.push_back(corner.vertex);
      faceHasUVs = faceHasUVs && corner.hasUV;
    }
    appendFan(polygon_, mesh_.triangles);
    if (allCornersHaveUV_ && !faceHasUVs) {
      allCornersHaveUV_ = false;
      mesh_.cornerUVs = {};  // one face without UVs means no UVs at all
    }
    if (allCornersHaveUV_) appendFanUVs();
  }

  void appendFanUVs() {
    const auto pushUV = [&](const Corner& corner) {
      mesh_.cornerUVs.push_back(texcoords_[static_cast<std::size_t>(corner.uv) * 2]);
      mesh_.cornerUVs.push_back(texcoords_[static_cast<std::size_t>(corner.uv) * 2 + 1]);
    };
    for (std::size_t i = 1; i + 1 < corners_.size(); ++i) {
      pushUV(corners_[0]);
      pushUV(corners_[i]);
      pushUV(corners_[i + 1]);
    }
  }

  const std::string& name_;
  std::size_t line_ = 0;
  SurfaceMesh mesh_;
  std::vector<float> texcoords_;  // u, v per vt statement
  bool allCornersHaveUV_ = true;
  bool sawStatement_ = false;
  std::vector<Corner> corners_;   // scratch, reused across faces
  std::vector<int32_t> polygon_;  // scratch, reused across faces
};

}  // namespace

SurfaceMesh loadObj(const uint8_t* data, std::size_t size, const std::string& name) {
  ObjParser parser(name);
  LineReader lines(data, size);
  std::string_view line;
  while (lines.next(line)) parser.parseLine(line, lines.lineNumber());
  return parser.finish();
}

}  // namespace tvf::io_detail
