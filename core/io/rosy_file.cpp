#include "io/rosy_file.h"

#include <cstdio>

#include "common/input_error.h"

namespace tvf {

std::string writeRosyFile(const std::vector<double>& faceDirections, int symmetry) {
  if (symmetry != 4)
    throw InputError(".rosy holds a cross field (symmetry 4); this design has symmetry " +
                     std::to_string(symmetry));
  const size_t numFaces = faceDirections.size() / 3;
  std::string out = std::to_string(numFaces) + "\n4\n";
  char line[96];
  for (size_t f = 0; f < numFaces; ++f) {
    const double* d = &faceDirections[3 * f];
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", d[0], d[1], d[2]);
    out += line;
  }
  return out;
}

}  // namespace tvf
