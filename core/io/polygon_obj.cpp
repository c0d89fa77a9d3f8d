#include "io/polygon_obj.h"

#include <cstdio>

namespace tvf {

std::string writePolygonObj(const QuadMesh& m, const std::string& comment) {
  std::string out;
  out.reserve(static_cast<std::size_t>(m.numVertices()) * 48 + m.faceVertices.size() * 10);
  if (!comment.empty()) out += "# " + comment + "\n";
  char line[128];
  for (int32_t v = 0; v < m.numVertices(); ++v) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", m.positions[3 * v], m.positions[3 * v + 1],
                  m.positions[3 * v + 2]);
    out += line;
  }
  for (int32_t f = 0; f < m.numFaces(); ++f) {
    out += 'f';
    for (int32_t k = m.faceStart[f]; k < m.faceStart[f + 1]; ++k)
      out += ' ' + std::to_string(m.faceVertices[k] + 1);
    out += '\n';
  }
  return out;
}

}  // namespace tvf
