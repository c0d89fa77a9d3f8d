#pragma once
// tvf's --ordering-cache DIR: the field's fill-reducing ordering and its symbolic factor kept in DIR, one
// file per mesh and field symmetry (io/ordering_file.h), so that opening the same mesh again skips the
// analysis (METIS on the mesh's vertex graph, then the elimination tree and supernodes: all of it before a
// big mesh's factorization).
#include <string>

#include "design/designer.h"

namespace tvf {

// Before the designer's first solve: the ordering kept in dir for its mesh and symmetry, adopted when there
// is a usable one. Returns what happened, in words (for --json and stderr): "none kept", "adopted", or why a
// file was ignored.
std::string adoptCachedOrdering(Designer& designer, const std::string& dir);
// After it: the ordering and symbolic factor written to dir unless the factorization took them from there
// (written whole, then renamed).
void keepOrdering(const Designer& designer, const std::string& dir);

}  // namespace tvf
