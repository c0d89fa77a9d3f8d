#pragma once
// Directional's singularity file (Vaxman et al.; directional::read_singularities / write_singularities in
// include/directional/): a first line "N count", then one line "vertex k" per singularity, whose index is k /
// N (k a nonzero integer). Directional's index prescription (its example 401) reads it; the design format's
// "singularities" (docs/design-format.md) hold the same pairs as vertex and index.
#include <string>
#include <vector>

#include "field/singularities.h"

namespace tvf {

// Each singularity's index must be a nonzero multiple of 1/symmetry (to 1e-9); throws InputError naming the
// first that is not, or a symmetry below 1.
std::string writeSingFile(int symmetry, const std::vector<Singularity>& singularities);

struct SingFile {
  int symmetry = 1;
  std::vector<Singularity> singularities;  // in the file's order; `prescribed` set (the file prescribes them)
};
// Throws InputError naming the line and the problem: a header that is not "N count" with 1 <= N <= 64, an
// entry that is not two integers, a negative vertex, an index numerator of 0, fewer or more entries than the
// header announces.
SingFile readSingFile(const std::string& text);

}  // namespace tvf
