#pragma once
// tvf's --ordering-cache DIR: the field's fill-reducing ordering kept in DIR, one file per mesh and field
// symmetry (io/ordering_file.h), so that opening the same mesh again skips the ordering (METIS on the mesh's
// vertex graph: most of the analysis before a big mesh's first field).
#include <string>

#include "design/designer.h"

namespace tvf {

// Before the designer's first solve: the ordering kept in dir for its mesh and symmetry, adopted when there
// is a usable one. Returns what happened, in words (for --json and stderr): "none kept", "adopted", or why a
// file was ignored.
std::string adoptCachedOrdering(Designer& designer, const std::string& dir);
// After it: the ordering written to dir unless the factorization reused it (written whole, then renamed).
void keepOrdering(const Designer& designer, const std::string& dir);

}  // namespace tvf
