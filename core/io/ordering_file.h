#pragma once
// A fill-reducing ordering kept on disk between runs (the CLI's --ordering-cache DIR): the field system's
// permutation and symbolic factor (solver/factored_system.h KeptOrdering) with the mesh it was computed on.
// Little-endian: "TVFORDER", version (u32, 2), ordering (u8: 0 AMD, 1 METIS), dissection (u8), 2 zero bytes,
// the mesh's hash (u64, mesh/mesh_hash.h), the matrix pattern's hash (u64), n (u64), n permutation entries
// (i32), m (u64) and the m bytes of the symbolic factor (solver/kept_symbolic.h symbolicBytes; none: m = 0),
// and an FNV-1a checksum (u64) of everything before it.
#include <cstdint>
#include <string>
#include <vector>

#include "solver/factored_system.h"

namespace tvf {

std::vector<uint8_t> orderingFileBytes(uint64_t meshHash, const KeptOrdering& kept);

// A file read back: the ordering, or none with the reason it was ignored (not such a file, another version,
// another mesh, cut short, a checksum that does not match). Whether it fits the matrix is the factor's to see
// (FactoredSystem::adoptOrdering, then the pattern's hash at factorization).
struct OrderingFile {
  KeptOrdering kept;
  std::string ignored;  // empty: kept is usable
};
OrderingFile readOrderingFile(const std::vector<uint8_t>& bytes, uint64_t meshHash);

}  // namespace tvf
