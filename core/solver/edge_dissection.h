#pragma once
// Nested dissection of a 1-form system by edge cuts of the mesh's vertex graph.
//
// Two edges couple in the 1-form Laplacian M only when they share a vertex. Split the vertices in two (an
// edge cut of the vertex graph, which METIS makes cheaply on a graph a third the size of M's, with 6 instead
// of 11 neighbours): the edges inside each half share no vertex with the other half's, so the edges crossing
// the cut separate M's graph. Where the matrix couples edges further apart (the bi-Laplacian M + g M *1^-1 M,
// the half boundary fluxes of free boundaries) the edges of one half that it couples to the other half join
// the separator, read from the matrix's own pattern.
#include <cstdint>
#include <vector>

#include "common/sparse_matrix.h"

namespace tvf {

struct EdgeDissection {
  // Constraint set of every edge for a constrained minimum-degree ordering (CAMD): sets numbered in postorder
  // of the dissection tree, so each subtree's edges come before the separator above them.
  std::vector<int32_t> constraintSet;
  // firstSet[s]: the smallest set number in the subtree of set s (s itself for a leaf).
  std::vector<int32_t> firstSet;
};

// edgeVertices: 2 per edge. A: the system (symmetric, one triangle or both stored; one row and column per
// edge), whose pattern decides which edges the separators must part. Parts with at most leafEdges edges are
// not cut further. parts: threads to cut independent parts on (common/thread_team.h); the dissection is the
// same on any number.
EdgeDissection dissectEdges(const std::vector<int32_t>& edgeVertices, int32_t numVertices, int32_t leafEdges,
                            const SparseMatrix& A, int parts = 1);

// Whether A (symmetric, one triangle or both stored) couples no two edges whose sets lie in different
// subtrees, i.e. the dissection's separators separate A.
bool separatesPattern(const EdgeDissection& dissection, const SparseMatrix& A);

}  // namespace tvf
