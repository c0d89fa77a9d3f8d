#pragma once
// The cycles of the dual graph (faces joined across interior edges) that a connection's holonomy is measured
// on: one around each interior vertex, and a basis of the rest (the surface's handles, and all but one of
// each component's boundary loops) from a tree-cotree decomposition (Eppstein 2003; Crane, Desbrun, Schroder
// 2010, Sec. 4). Together they span every dual cycle, independently once each closed component drops one
// vertex cycle (their sum vanishes there). A spanning tree of the dual graph comes with them: a connection
// whose holonomy is a multiple of 2 pi / N on every one of these cycles can be integrated along it.
#include <cstdint>
#include <vector>

#include "direction/levi_civita_connection.h"
#include "mesh/mesh_topology.h"

namespace tvf {

// A dual cycle: connection entries (FaceConnection order) with +1 where the cycle crosses from faceG to
// faceF (the direction in which the entry's angle is added) and -1 against it.
struct DualCycle {
  std::vector<int32_t> entries;
  std::vector<int8_t> signs;
};

struct DualCycles {
  std::vector<int32_t> edgeOfEntry;  // the mesh edge of each connection entry
  // Per entry: the vertex at its edge's higher and lower end and the sign with which the counter-clockwise
  // cycle around each crosses it (opposite signs, so a cycle around one vertex only needs one sign stored).
  std::vector<int32_t> entryHigh, entryLow;
  std::vector<int8_t> highSign;  // the lower end's sign is -highSign
  // Row of each vertex's cycle in the holonomy system; -1 for boundary vertices and for the one vertex per
  // closed component whose cycle is implied by the others.
  std::vector<int32_t> vertexRow;
  int32_t vertexRows = 0;
  std::vector<DualCycle> generators;
  // The dual spanning forest in breadth-first order: each face after its parent (parentEntry -1: a root).
  std::vector<int32_t> treeOrder, parentEntry;
};

DualCycles dualCycles(const MeshTopology& topology, const FaceConnection& connection);

}  // namespace tvf
