#pragma once
// Where an edit's stripe pattern has to change, and the pattern's linear systems solved there alone.
//
// A stroke moves the field by more than half a degree at 10-33 % of bunny00's vertices (a line field after 15
// strokes, twelve strokes more), and by more than five at 6-12 %, yet its eigenvector slides the whole
// pattern. Solved on the vertices that moved and some periods around them, with the last pattern held fixed
// beyond, the stripes change where the field changed and stay where it did not (stripe_pattern.h:
// StripeOptions::localUpdate). The spacing that lets the stripes follow the field is fixed along the field's
// lines, and a change heals over a period or two: on a torus whose field turned by up to 20 degrees in one
// place, the stripes there were 4.6 degrees off it with two rings of edges round every vertex moved by a
// quarter of a degree, 3.0 with two periods, 2.2 made afresh.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include "mesh/mesh_topology.h"

namespace tvf {

// The vertices an edit's pattern is solved for, and what its systems read around them: the faces with a
// vertex in it and their edges. A local update loops over these lists alone (bunny00's 2.6-10k of 38k
// vertices), never over the whole mesh.
struct StripeRegion {
  std::vector<int32_t> local;     // per vertex: its index among the region's vertices, or -1 outside it
  std::vector<int32_t> vertices;  // by index in the region
  std::vector<int32_t> faces;     // ascending: the faces with a vertex in the region
  std::vector<int32_t> edges;     // ascending: the edges of those faces
  // A fill-reducing ordering of the region's vertices (regionOrdering), made once for both of its systems.
  std::vector<int> ordering;
  int32_t size = 0;
};

// Whether a face (its three vertices) has a vertex in the region.
inline bool faceReaches(const StripeRegion& region, const int32_t* v) {
  return region.local[v[0]] >= 0 || region.local[v[1]] >= 0 || region.local[v[2]] >= 0;
}

// The vertices where `changed` is set and those up to `rings` edges away from them, with the faces and edges
// that reach them (triangles: the mesh's, three per face).
StripeRegion grownRegion(const MeshTopology& t, const std::vector<int32_t>& triangles,
                         const std::vector<uint8_t>& changed, int rings);

// The elements a loop visits: all n of a mesh's, or those a list names (a region's).
struct Elements {
  const std::vector<int32_t>* list = nullptr;
  int32_t n = 0;
  int32_t size() const { return list ? static_cast<int32_t>(list->size()) : n; }
  int32_t operator[](int32_t i) const { return list ? (*list)[static_cast<size_t>(i)] : i; }
};

// Solves the rows of A x = b that belong to the region with x held at its given values elsewhere:
// A_RR x_R = b_R - A_RB x_B. `upper`: A's upper-triangle entries (repeated entries summed) over n unknowns,
// of which `per` consecutive ones belong to each vertex. b: empty for 0. ordering: a fill-reducing ordering
// of the region's unknowns (SpdFactor's); empty: AMD. Returns false where A_RR is not positive definite or
// the solve fails (x untouched then).
bool solveOnRegion(const std::vector<Eigen::Triplet<double>>& upper, const Eigen::VectorXd& b,
                   const StripeRegion& region, int per, Eigen::VectorXd& x, std::vector<int> ordering = {});

// The region's vertices (their indices in it) in the order a fill-reducing ordering of all the mesh's
// vertices (a big mesh's nested dissection) puts them; for an empty one, AMD's ordering of the region's own
// vertex graph (a system of several unknowns a vertex, expanded, is analysed in a fraction of the time AMD
// takes on its rows: bunny00's local updates' energy, 7-14k rows, 3-7 ms).
std::vector<int> regionOrdering(const MeshTopology& t, const StripeRegion& region,
                                const std::vector<int>& vertexOrdering);

}  // namespace tvf
