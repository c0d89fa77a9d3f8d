#pragma once
// QuadWild's per-face cross field (.rosy; Pietroni et al., read by vcglib's ImporterFIELD::Load4ROSY, which
// QuadWild's LoadField calls for a file ending in .rosy): a line with the face count, a line "4", then one
// line "x y z" per face in the mesh's face order, one of the face's four directions. The reader takes the
// second direction as that one crossed with the face normal, so any of the four serves.
#include <string>
#include <vector>

namespace tvf {

// faceDirections: 3 per face (a unit representative). Throws InputError unless symmetry is 4: the reader
// asserts a cross field. Rounded to 9 decimals (the reader parses floats).
std::string writeRosyFile(const std::vector<double>& faceDirections, int symmetry);

}  // namespace tvf
