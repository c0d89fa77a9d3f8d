#pragma once
// The supernodal symbolic factor of a fill-reducing ordering, kept beyond the system that computed it with
// the ordering (solver/factored_system.h KeptOrdering): the same pattern then factors again with no symbolic
// analysis at all, only the permuted lower triangle its numeric factorization assembles from. It depends on
// the matrix's pattern alone, like the ordering: 0.5 s of a big model's reopening in the page
// (armadillo-sub2, 1.25M edges: its elimination tree, column counts and supernodes, 35 MB of supernodal row
// indices).
//
// A kept one is checked against the matrix before it is used (solver/symbolic_analysis.h symbolicFromKept).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tvf {

// CHOLMOD's L->super and L->pi (nsuper + 1 each: each supernode's first column and the start of its rows in
// s) and L->s (the rows), of a supernodal symbolic factor. The rest of it (L->px, the column counts, the
// largest update and solve blocks) follows from these and is derived again.
struct KeptSymbolic {
  std::vector<int32_t> super, pi, s;

  bool empty() const { return super.empty(); }
};

// The symbolic factor of the same graph with `per` unknowns to each of its nodes, a node's kept together and
// in its place (rows r -> per r .. per r + per - 1, as the ordering expanded so): block elimination fills
// whole blocks where the node's elimination filled an entry. Empty for an empty one.
KeptSymbolic expandedSymbolic(const KeptSymbolic& k, int per);

// Its bytes for a cache: per supernode, its number of columns and of rows below them, then those rows as
// increasing steps from its last column, each an unsigned LEB128 varint (armadillo-sub2: 8.8 MB where the
// three arrays take 38 MB). Empty for an empty one.
std::vector<uint8_t> symbolicBytes(const KeptSymbolic& k);
// The symbolic factor those bytes give; empty where they are cut short or out of range (the analysis then
// runs). Whether it fits a matrix is checked where it is used.
KeptSymbolic symbolicFromBytes(const uint8_t* bytes, size_t size);

}  // namespace tvf
