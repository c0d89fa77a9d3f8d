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

#include "common/sparse_matrix.h"
#include "mesh/mesh_topology.h"
#include "solver/kept_symbolic.h"

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

// What a region system's solve was analysed with: the symbolic factor and the permutation of its unknowns
// (the ordering with its postorder folded in), `per` unknowns to a vertex. The spacing's (one a vertex)
// serves the energy's (2F), whose graph is the same with whole blocks: its analysis was 2.5 of its 8 ms in
// wasm on bunny00.
struct RegionAnalysis {
  KeptSymbolic symbolic;
  std::vector<int> permutation;
  int per = 0;
};

// The rows of A x = b that belong to the region, with x held at its given values elsewhere: A_RR x_R = b_R -
// A_RB x_B, assembled in the region's own numbering as the entries come (in wasm, a 23 ms local update on
// bunny00 spent 4.5 ms listing its entries, moving them into the region's numbering and sorting them; in
// place, 1-2 ms less in all). `per` consecutive unknowns of x belong to each vertex. A_RR's pattern holds
// every pair of unknowns of one region vertex or of two neighbouring ones: the spacing's and the energy's
// entries all lie there.
class RegionSystem {
 public:
  // x: the held values (read as entries come, until solve()).
  RegionSystem(const MeshTopology& t, const StripeRegion& region, int per, const Eigen::VectorXd& x);
  // Adds `value` to A's entries (i, j) and (j, i) (each pair given once; i == j: the diagonal), in x's
  // numbering; nothing where neither is in the region.
  void add(int32_t i, int32_t j, double value);
  void addRhs(int32_t i, double value);  // to b's entry i
  void reserve(size_t) {}                // as TripletSystem's: nothing to do, the pattern is made up front
  // Factors A_RR with `vertexOrdering` (of the region's vertices: regionOrdering; empty: AMD's of its
  // unknowns), or with `given`'s analysis expanded where it has fewer unknowns to a vertex, solves, and
  // writes x_R into x; `made`: this one's analysis. False where an entry fell outside the pattern, A_RR is
  // not positive definite or the solve failed (x untouched then).
  bool solve(const std::vector<int>& vertexOrdering, Eigen::VectorXd& x,
             const RegionAnalysis* given = nullptr, RegionAnalysis* made = nullptr) const;

 private:
  int32_t localOf(int32_t i) const {
    const int32_t v = region_.local[static_cast<size_t>(i / per_)];
    return v < 0 ? -1 : v * per_ + i % per_;
  }

  const StripeRegion& region_;
  int per_;
  const Eigen::VectorXd& held_;
  SparseMatrix upper_;  // compressed, its pattern made up front, values summed in place
  Eigen::VectorXd rhs_;
  bool missed_ = false;
};

// A vertex ordering for `per` unknowns to a vertex, each vertex's kept together in its place.
std::vector<int> expandedOrdering(const std::vector<int>& vertices, int per);

// The region's vertices (their indices in it) in the order a fill-reducing ordering of all the mesh's
// vertices (a big mesh's nested dissection) puts them; for an empty one, AMD's ordering of the region's own
// vertex graph (a system of several unknowns a vertex, expanded, is analysed in a fraction of the time AMD
// takes on its rows: bunny00's local updates' energy, 7-14k rows, 3-7 ms).
std::vector<int> regionOrdering(const MeshTopology& t, const StripeRegion& region,
                                const std::vector<int>& vertexOrdering);

}  // namespace tvf
