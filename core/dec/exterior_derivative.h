#pragma once
// Signed incidence matrices: d0 (|E|x|V|, -1 at the tail, +1 at the head) and d1 (|F|x|E|, +/-1 as the edge
// agrees/disagrees with the face's boundary orientation). Integer-valued, so d1 d0 = 0 exactly.
#include "common/sparse_matrix.h"
#include "mesh/mesh_topology.h"

namespace tvf {

SparseMatrix exteriorDerivative0(const MeshTopology& topology);
SparseMatrix exteriorDerivative1(const MeshTopology& topology);

}  // namespace tvf
