#include "io/raw_field.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/input_error.h"

namespace tvf {

std::string writeRawField(const std::vector<double>& faceDirections, const std::vector<double>& faceNormals,
                          int symmetry) {
  const size_t numFaces = faceDirections.size() / 3;
  std::string out = std::to_string(symmetry) + " " + std::to_string(numFaces) + "\n";
  char number[40];
  for (size_t f = 0; f < numFaces; ++f) {
    const double* d = &faceDirections[3 * f];
    const double* n = &faceNormals[3 * f];
    const double cross[3] = {n[1] * d[2] - n[2] * d[1], n[2] * d[0] - n[0] * d[2], n[0] * d[1] - n[1] * d[0]};
    for (int k = 0; k < symmetry; ++k) {
      const double angle = 2 * M_PI * k / symmetry;
      for (int i = 0; i < 3; ++i) {
        std::snprintf(number, sizeof number, "%.17g", std::cos(angle) * d[i] + std::sin(angle) * cross[i]);
        out += number;
        out += k + 1 == symmetry && i == 2 ? '\n' : ' ';
      }
    }
  }
  return out;
}

RawField readRawField(const std::string& text) {
  std::istringstream in(text);
  RawField field;
  long long numFaces = -1;
  if (!(in >> field.symmetry >> numFaces) || field.symmetry < 1 || field.symmetry > 64 || numFaces < 0)
    throw InputError("not a raw field: the first line must be \"N numF\"");
  field.directions.resize(static_cast<size_t>(numFaces) * 3 * field.symmetry);
  for (size_t k = 0; k < field.directions.size(); ++k) {
    if (!(in >> field.directions[k]))
      throw InputError("raw field: face " + std::to_string(k / (3 * field.symmetry)) +
                       " has too few numbers");
    if (!std::isfinite(field.directions[k]))
      throw InputError("raw field: face " + std::to_string(k / (3 * field.symmetry)) +
                       " has a number that is "
                       "not finite");
  }
  return field;
}

}  // namespace tvf
