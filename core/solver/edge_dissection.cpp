#include "solver/edge_dissection.h"

#include <metis.h>

#include <algorithm>
#include <array>
#include <exception>
#include <memory>
#include <numeric>
#include <utility>

#include "common/thread_team.h"

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

// A node of the dissection tree: a leaf's edges, or a separator's edges and the two parts it separates.
struct Node {
  std::vector<int32_t> edges;
  std::unique_ptr<Node> child[2];
};

class Dissector {
 public:
  Dissector(const std::vector<int32_t>& edgeVertices, int32_t numVertices, int32_t leafEdges,
            const SparseMatrix& A, int parts)
      : ev_(edgeVertices), A_(A), leafEdges_(leafEdges), numVertices_(numVertices), parts_(parts) {
    const int32_t nE = static_cast<int32_t>(edgeVertices.size() / 2);
    edgeSide_.assign(nE, -1);
    out_.constraintSet.assign(nE, 0);
    widen_ = !couplesOnlyThroughVertices();
  }

  // The tree is grown first, the top levels one at a time with their parts side by side until there is a
  // subtree per thread, then those subtrees on the threads; its sets are numbered after, in postorder, so the
  // dissection is the same on any number of threads.
  EdgeDissection run() {
    Node root;
    std::vector<Growing> frontier;
    frontier.push_back({&root, wholeGraph()});
    ThreadTeam* team = nullptr;
    if (parts_ > 1) {
      try {
        team = &ThreadTeam::shared();
        parts_ = std::min(parts_, ThreadTeam::maxParts());
      } catch (const std::exception&) {
        team = nullptr;
      }
    }
    if (!team) parts_ = 1;
    while (parts_ > 1 && !frontier.empty() && static_cast<int>(frontier.size()) < parts_) {
      std::vector<std::vector<Growing>> next(frontier.size());
      runEach(*team, static_cast<int>(frontier.size()), [&](int k) { next[k] = split(frontier[k]); });
      std::vector<Growing> deeper;
      for (std::vector<Growing>& kids : next)
        for (Growing& kid : kids) deeper.push_back(std::move(kid));
      frontier.swap(deeper);
    }
    if (parts_ > 1 && frontier.size() > 1) {
      const std::vector<std::vector<int>> groups = largestFirst(frontier, parts_);
      runEach(*team, static_cast<int>(groups.size()), [&](int g) {
        for (const int k : groups[g]) grow(frontier[k]);
      });
    } else {
      for (Growing& f : frontier) grow(f);
    }
    number(root);
    return std::move(out_);
  }

 private:
  struct Growing {
    Node* node;
    Part graph;
  };

  // task(k) for k < parts on the team; a task's exception (memory running out) is rethrown here, since the
  // team's tasks must not throw.
  template <class Task>
  static void runEach(ThreadTeam& team, int parts, const Task& task) {
    std::vector<std::exception_ptr> failed(parts);
    team.run(parts, [&](int k) {
      try {
        task(k);
      } catch (...) {
        failed[k] = std::current_exception();
      }
    });
    for (const std::exception_ptr& e : failed)
      if (e) std::rethrow_exception(e);
  }

  // The frontier's parts in at most `parts` groups of about equal edges, the largest first to the lightest.
  static std::vector<std::vector<int>> largestFirst(const std::vector<Growing>& frontier, int parts) {
    std::vector<int> order(frontier.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return frontier[a].graph.edges() > frontier[b].graph.edges(); });
    const int groups = std::min(parts, static_cast<int>(frontier.size()));
    std::vector<std::vector<int>> out(groups);
    std::vector<int64_t> load(groups, 0);
    for (const int k : order) {
      const int g = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
      out[g].push_back(k);
      load[g] += frontier[k].graph.edges();
    }
    return out;
  }

  void grow(Growing& g) {
    for (Growing& kid : split(g)) grow(kid);
  }

  // Sets numbered in postorder: each part's before the separator above it.
  void number(const Node& node) {
    const int32_t first = static_cast<int32_t>(out_.firstSet.size());
    if (node.child[0]) {
      number(*node.child[0]);
      number(*node.child[1]);
    }
    out_.firstSet.push_back(first);
    const int32_t set = static_cast<int32_t>(out_.firstSet.size()) - 1;
    for (const int32_t e : node.edges) out_.constraintSet[e] = set;
  }

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

  // One bisection of the node's part: its two sides to grow (the node then holds the separator), or none (the
  // node is a leaf and holds the part's edges). The part's arrays are let go here.
  std::vector<Growing> split(Growing& growing) {
    Node& node = *growing.node;
    Part g = std::move(growing.graph);
    std::vector<idx_t> part;
    const auto leaf = [&] {
      g.forEachEdge([&](int32_t e) { node.edges.push_back(e); });
      return std::vector<Growing>();
    };
    if (g.edges() <= leafEdges_ || !bisect(g, part)) return leaf();
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
    std::array<Part, 2> halves = sides(g, part);
    if (widen_)
      for (const int32_t e : separator) edgeSide_[e] = -1;
    if (halves[0].edges() == 0 || halves[1].edges() == 0) return leaf();  // no useful cut
    node.edges = std::move(separator);
    std::vector<Growing> kids;
    for (int s = 0; s < 2; ++s) {
      node.child[s] = std::make_unique<Node>();
      kids.push_back({node.child[s].get(), std::move(halves[s])});
    }
    return kids;
  }

  // The two sides of `g`: each side's vertices and the edges between them that are not in the separator
  // (marked kSeparator in edgeSide_ where the separator was widened), numbered in g's order; one pass over g.
  std::array<Part, 2> sides(const Part& g, const std::vector<idx_t>& part) const {
    const idx_t n = g.vertices();
    std::vector<idx_t> local(n);
    idx_t count[2] = {0, 0};
    for (idx_t k = 0; k < n; ++k) local[k] = count[part[k]]++;
    std::array<Part, 2> c;
    for (int s = 0; s < 2; ++s) {
      c[s].xadj.reserve(count[s] + 1);
      c[s].adjncy.reserve(g.adjncy.size() / 2);
      c[s].edge.reserve(g.adjncy.size() / 2);
    }
    for (idx_t k = 0; k < n; ++k) {
      Part& side = c[part[k]];
      for (idx_t p = g.xadj[k]; p < g.xadj[k + 1]; ++p) {
        const idx_t j = g.adjncy[p];
        if (part[j] != part[k] || (widen_ && edgeSide_[g.edge[p]] == kSeparator)) continue;
        side.adjncy.push_back(local[j]);
        side.edge.push_back(g.edge[p]);
      }
      side.xadj.push_back(static_cast<idx_t>(side.adjncy.size()));
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
    // METIS takes the arrays as non-const but only reads them. Its random generator is per thread (the
    // build's wasm/patches/metis-gklib-thread-random.patch), seeded on entry: the same part gives the same
    // cut on any thread.
    auto* xadj = const_cast<idx_t*>(g.xadj.data());
    auto* adjncy = const_cast<idx_t*>(g.adjncy.data());
    return METIS_PartGraphRecursive(&nv, &constraints, xadj, adjncy, weight.data(), nullptr, nullptr, &parts,
                                    nullptr, nullptr, options, &cut, part.data()) == METIS_OK;
  }

  const std::vector<int32_t>& ev_;
  const SparseMatrix& A_;
  int32_t leafEdges_, numVertices_;
  int parts_;
  std::vector<int32_t> edgeSide_;
  bool widen_ = true;
  EdgeDissection out_;
};

}  // namespace

EdgeDissection dissectEdges(const std::vector<int32_t>& edgeVertices, int32_t numVertices, int32_t leafEdges,
                            const SparseMatrix& A, int parts) {
  return Dissector(edgeVertices, numVertices, leafEdges, A, parts).run();
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
