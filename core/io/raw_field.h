#pragma once
// The "raw field" text format of Directional (Vaxman et al.; directional::read_raw_field / write_raw_field),
// which its quad-meshing and integration tools read: a first line "N numF", then one line per face with the
// N directions of that face as x y z triples, in counter-clockwise order about the face normal. Faces are in
// the mesh's face order (for this project, the welded mesh's: docs/design-format.md).
#include <string>
#include <vector>

namespace tvf {

// faceDirections: one unit representative per face; faceNormals: 3 per face, unit. The other directions are
// the representative rotated by 2 pi k / N about the normal. 17 significant digits.
std::string writeRawField(const std::vector<double>& faceDirections, const std::vector<double>& faceNormals,
                          int symmetry);

struct RawField {
  int symmetry = 0;
  std::vector<double> directions;  // 3 N per face
};
// Throws InputError naming the first problem (a bad header, too few numbers, a number that is not finite).
RawField readRawField(const std::string& text);

}  // namespace tvf
