#include "solver/edge_dissection.h"

#include <metis.h>

#include <algorithm>
#include <numeric>
#include <utility>

namespace tvf {
namespace {

// A part of the vertex graph in its own numbering: each vertex's neighbours within the part (in the order of
// the mesh's incidence lists) and, beside each, the mesh edge that joins them. Every edge of the part shows
// twice, once from each end. A child is cut from its parent's arrays in one pass over them: the global
// incidence lists, visited in the mesh's order, took most of the dissection's own time in cache misses.
struct Part {
  std::vector<idx_t> xadj{0}, adjncy;
  std::vector<int32_t> edge;
  idx_t vertices() const { return static_cast<idx_t>(xadj.size()) - 1; }
  int32_t edges() const { return static_cast<int32_t>(adjncy.size() / 2); }
  // f(edge) once per edge of the part.
  template <class F>
  void forEachEdge(F&& f) const {
    const idx_t n = vertices();
    for (idx_t k = 0; k < n; ++k)
      for (idx_t p = xadj[k]; p < xadj[k + 1]; ++p)
        if (adjncy[p] > k) f(edge[p]);
  }
};

class Dissector {
 public:
  Dissector(const std::vector<int32_t>& edgeVertices, int32_t numVertices, int32_t leafEdges,
            const SparseMatrix& A)
      : ev_(edgeVertices), A_(A), leafEdges_(leafEdges), numVertices_(numVertices) {
    const int32_t nE = static_cast<int32_t>(edgeVertices.size() / 2);
    edgeSide_.assign(nE, -1);
    out_.constraintSet.assign(nE, 0);
    widen_ = !couplesOnlyThroughVertices();
  }

  EdgeDissection run() {
    dissect(wholeGraph());
    return std::move(out_);
  }

 private:
  // The mesh's vertex graph: each vertex's edges in edge order, as the incidence lists list them.
  Part wholeGraph() const {
    const int32_t nV = numVertices_, nE = static_cast<int32_t>(ev_.size() / 2);
    Part g;
    g.xadj.assign(nV + 1, 0);
    for (const int32_t v : ev_) ++g.xadj[v + 1];
    for (int32_t v = 0; v < nV; ++v) g.xadj[v + 1] += g.xadj[v];
    g.adjncy.resize(ev_.size());
    g.edge.resize(ev_.size());
    std::vector<idx_t> fill(g.xadj.begin(), g.xadj.end() - 1);
    for (int32_t e = 0; e < nE; ++e)
      for (int k = 0; k < 2; ++k) {
        const idx_t p = fill[ev_[2 * e + k]]++;
        g.adjncy[p] = ev_[2 * e + 1 - k];
        g.edge[p] = e;
      }
    return g;
  }

  // Whether every pair of edges the matrix couples shares a vertex (the 1-form Laplacian's pattern: edges of
  // one vertex star or one face). Then an edge cut of the vertex graph separates the matrix as it is, and no
  // separator needs widening.
  bool couplesOnlyThroughVertices() const {
    for (int32_t j = 0; j < A_.outerSize(); ++j) {
      const int32_t a = ev_[2 * j], b = ev_[2 * j + 1];
      for (SparseMatrix::InnerIterator it(A_, j); it; ++it) {
        const int32_t c = ev_[2 * it.row()], d = ev_[2 * it.row() + 1];
        if (a != c && a != d && b != c && b != d) return false;
      }
    }
    return true;
  }

  int32_t newSet(int32_t first) {
    out_.firstSet.push_back(first);
    return static_cast<int32_t>(out_.firstSet.size()) - 1;
  }

  void assign(const Part& g, int32_t set) {
    g.forEachEdge([&](int32_t e) { out_.constraintSet[e] = set; });
  }

  void dissect(Part g) {
    const int32_t first = static_cast<int32_t>(out_.firstSet.size());
    std::vector<idx_t> part;
    if (g.edges() <= leafEdges_ || !bisect(g, part)) {
      assign(g, newSet(first));
      return;
    }
    std::vector<int32_t> separator, sideEdges[2];
    const idx_t n = g.vertices();
    for (idx_t k = 0; k < n; ++k)
      for (idx_t p = g.xadj[k]; p < g.xadj[k + 1]; ++p) {
        const idx_t j = g.adjncy[p];
        if (j < k) continue;
        if (part[k] != part[j])
          separator.push_back(g.edge[p]);
        else if (widen_)
          sideEdges[part[k]].push_back(g.edge[p]);
      }
    if (widen_) widenSeparator(sideEdges, separator);
    Part sides[2] = {side(g, part, 0), side(g, part, 1)};
    if (sides[0].edges() == 0 || sides[1].edges() == 0) {  // no useful cut
      for (const int32_t e : separator) edgeSide_[e] = -1;
      assign(g, newSet(first));
      return;
    }
    for (const int32_t e : separator) edgeSide_[e] = -1;
    g = Part();
    dissect(std::move(sides[0]));
    dissect(std::move(sides[1]));
    const int32_t set = newSet(first);
    for (const int32_t e : separator) out_.constraintSet[e] = set;
  }

  // The vertices of `g` on side `s` and the edges between them that are not in the separator (marked
  // kSeparator in edgeSide_ where the separator was widened), numbered in g's order.
  Part side(const Part& g, const std::vector<idx_t>& part, idx_t s) const {
    const idx_t n = g.vertices();
    std::vector<idx_t> local(n, -1);
    idx_t count = 0;
    for (idx_t k = 0; k < n; ++k)
      if (part[k] == s) local[k] = count++;
    Part c;
    c.xadj.reserve(count + 1);
    c.adjncy.reserve(g.adjncy.size() / 2);
    c.edge.reserve(g.adjncy.size() / 2);
    for (idx_t k = 0; k < n; ++k) {
      if (part[k] != s) continue;
      for (idx_t p = g.xadj[k]; p < g.xadj[k + 1]; ++p) {
        const idx_t j = g.adjncy[p];
        if (part[j] != s || (widen_ && edgeSide_[g.edge[p]] == kSeparator)) continue;
        c.adjncy.push_back(local[j]);
        c.edge.push_back(g.edge[p]);
      }
      c.xadj.push_back(static_cast<idx_t>(c.adjncy.size()));
    }
    return c;
  }

  static constexpr int32_t kCoupled = 2, kSeparator = 3;

  // Edges of side 0 that the matrix couples to side 1 join the separator (none for the plain Laplacian). Each
  // coupling is stored in one column or both (the upper triangle: the later edge's), so both sides' columns
  // are read; kCoupled marks a side-0 edge found coupled. The widened separator's edges stay marked
  // kSeparator until the sides are cut.
  void widenSeparator(std::vector<int32_t> (&side)[2], std::vector<int32_t>& separator) {
    for (int k = 0; k < 2; ++k)
      for (const int32_t e : side[k]) edgeSide_[e] = k;
    for (const int32_t e : side[0])
      for (SparseMatrix::InnerIterator it(A_, e); it && edgeSide_[e] != kCoupled; ++it)
        if (edgeSide_[it.row()] == 1) edgeSide_[e] = kCoupled;
    for (const int32_t f : side[1])
      for (SparseMatrix::InnerIterator it(A_, f); it; ++it)
        if (edgeSide_[it.row()] == 0) edgeSide_[it.row()] = kCoupled;
    for (const int32_t e : side[0])
      if (edgeSide_[e] == kCoupled) separator.push_back(e);
    for (int k = 0; k < 2; ++k)
      for (const int32_t e : side[k]) edgeSide_[e] = -1;
    for (const int32_t e : separator) edgeSide_[e] = kSeparator;
  }

  // An edge-cut bisection of the part's graph, weighted by vertex degree so that the halves hold about as
  // many edges.
  bool bisect(const Part& g, std::vector<idx_t>& part) const {
    const idx_t n = g.vertices();
    std::vector<idx_t> weight(n);
    for (idx_t k = 0; k < n; ++k) weight[k] = 1 + g.xadj[k + 1] - g.xadj[k];
    idx_t constraints = 1, parts = 2, cut = 0;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    // One cut (METIS's default). The better of two buys 1.5-2 % of fill (bunny00 51.2 against 52.0 nnz/row,
    // 1.25M edges 66.5 against 68.0) and no stroke time measurable in interleaved runs, for 40-45 % more
    // analysis (bunny00 223-266 against 164-185 ms, 1.25M edges 4.9-5.3 against 3.3-3.8 s; README).
    part.assign(n, 0);
    idx_t nv = n;
    // METIS takes the arrays as non-const but only reads them.
    auto* xadj = const_cast<idx_t*>(g.xadj.data());
    auto* adjncy = const_cast<idx_t*>(g.adjncy.data());
    return METIS_PartGraphRecursive(&nv, &constraints, xadj, adjncy, weight.data(), nullptr, nullptr, &parts,
                                    nullptr, nullptr, options, &cut, part.data()) == METIS_OK;
  }

  const std::vector<int32_t>& ev_;
  const SparseMatrix& A_;
  int32_t leafEdges_, numVertices_;
  std::vector<int32_t> edgeSide_;
  bool widen_ = true;
  EdgeDissection out_;
};

}  // namespace

EdgeDissection dissectEdges(const std::vector<int32_t>& edgeVertices, int32_t numVertices, int32_t leafEdges,
                            const SparseMatrix& A) {
  return Dissector(edgeVertices, numVertices, leafEdges, A).run();
}

bool separatesPattern(const EdgeDissection& dissection, const SparseMatrix& A) {
  const std::vector<int32_t>& set = dissection.constraintSet;
  const std::vector<int32_t>& first = dissection.firstSet;
  auto inSubtree = [&](int32_t s, int32_t root) { return first[root] <= s && s <= root; };
  for (int32_t j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const int32_t a = set[it.row()], b = set[j];
      if (!inSubtree(a, b) && !inSubtree(b, a)) return false;
    }
  return true;
}

}  // namespace tvf
