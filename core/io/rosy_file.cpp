#include "io/rosy_file.h"

#include <cmath>
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
    // A unit vector to 9 decimals, as 9 digits of its larger components: a small component's further digits
    // are round-off, which would make two solves of the same field (the page's and the CLI's) write different
    // bytes. (+ 0.0 writes -0 as 0.)
    const auto digits = [](double x) { return std::round(x * 1e9) / 1e9 + 0.0; };
    const double* d = &faceDirections[3 * f];
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", digits(d[0]), digits(d[1]), digits(d[2]));
    out += line;
  }
  return out;
}

}  // namespace tvf
