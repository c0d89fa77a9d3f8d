#include "solver/supernodal_cholesky.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "common/thread_team.h"
#include "solver/dense_cholesky.h"
#include "solver/dense_kernels.h"
#include "solver/permuted_triangle.h"
#include "solver/subtree_partition.h"
#include "solver/supernodes.h"

namespace tvf {
namespace {

std::atomic<bool> failThreadsOnce{false};
std::atomic<bool> ownFactorizationAlone{true};

// One thread's scratch: row positions within the supernode being factored (indexed by row of L), the
// descendants' rows mapped to them, and the update block of one descendant.
struct Workspace {
  std::vector<int> map, relativeMap;
  std::vector<double> c;
  std::vector<int> pending;      // descendants whose next ancestor lies above the subtrees, for after them
  std::vector<int> descendants;  // the supernode's descendants in the order their updates are summed
};

// The parts of a large supernode's work, whatever the threads: its rows in bands (2 to kBands, by its size
// alone) for the descendants' updates and for its dense block (solver/dense_cholesky.h), which the threads
// share out. Each band's sums are then the same operations in the same order on one thread or sixteen, and so
// are every other supernode's (its descendants taken in index order, not in the order other threads finished
// them): the factor is the same bit for bit on any number of threads. Every band costs a call per descendant,
// so a supernode gets one per 5e8 multiply-adds (at least two): sixteen on bunny00 made one thread's
// factorization 15 % slower, two took no more time than none.
constexpr int kBands = 16;

class Factorization {
 public:
  // A supernode with dense work (nscol^2 nsrow) above kBandedFlops is factored in work / kFlopsPerBand bands
  // (2 to kBands): on all threads at the top, on its group's thread in a subtree.
  static constexpr double kBandedFlops = 4e6, kFlopsPerBand = 5e8;

  Factorization(const Supernodes& sn, const PermutedTriangle& S) : sn_(sn), S_(S) {
    superMap_.resize(sn.n);
    for (int s = 0; s < sn.count; ++s) std::fill(&superMap_[sn.super[s]], &superMap_[sn.super[s + 1]], s);
    head_.assign(sn.count, -1);
    next_.assign(sn.count, -1);
    lpos_.assign(sn.count, 0);
    parent_.resize(sn.count);
    work_.resize(sn.count);
    for (int s = 0; s < sn.count; ++s) {
      const int nscol = sn.cols(s), nsrow = sn.rows(s);
      parent_[s] = nsrow > nscol ? superMap_[sn.ls[sn.pi[s] + nscol]] : -1;
      // Its own dense work and the update it sends up, which its ancestors' thread does.
      work_[s] = 1 + static_cast<int64_t>(nscol) * nsrow * nsrow;
    }
  }

  const std::vector<int>& parent() const { return parent_; }
  const std::vector<int64_t>& work() const { return work_; }
  int failedColumn() const { return failed_.load(); }
  int bandedSupernodes() const { return banded_.load(); }

  void prepare(Workspace& w, size_t maxcsize, bool withMaps = true) const {
    if (withMaps) {
      w.map.assign(sn_.n, -1);
      w.relativeMap.resize(sn_.n);
    }
    w.c.resize(maxcsize);
  }

  // The top's supernodes (descending), after the subtrees: the banded ones on all `parts` threads
  // (spaces[0] with maps, the others with an update block), the rest on this one.
  void factorTop(const std::vector<int>& nodes, std::vector<Workspace>& spaces, int parts,
                 const std::vector<char>& mine) {
    for (auto it = nodes.rbegin(); it != nodes.rend(); ++it) {
      if (failed_.load(std::memory_order_relaxed) < sn_.n) return;
      if (bandsOf(*it) > 0)
        factorBanded(*it, spaces.data(), parts, mine);
      else
        factorOne(*it, spaces[0], mine);
    }
  }

  // Supernodes `nodes` (descending) on this thread, each after its descendants; a descendant whose next
  // ancestor is not `mine` (another thread's, or the top's) waits in w.pending.
  void factorAll(const std::vector<int>& nodes, Workspace& w, const std::vector<char>& mine) {
    for (auto it = nodes.rbegin(); it != nodes.rend(); ++it) {
      if (failed_.load(std::memory_order_relaxed) < sn_.n) return;
      if (bandsOf(*it) > 0)
        factorBanded(*it, &w, 1, mine);
      else
        factorOne(*it, w, mine);
    }
  }

  // Links the descendants that waited for an ancestor above the subtrees, in the groups' order.
  void linkPending(Workspace& w) {
    for (const int d : w.pending) link(d, superMap_[sn_.ls[sn_.pi[d] + lpos_[d]]]);
    w.pending.clear();
  }

 private:
  int bandsOf(int s) const {
    const double nscol = sn_.cols(s), nsrow = sn_.rows(s), flops = nscol * nscol * nsrow;
    if (!(flops > kBandedFlops)) return 0;
    return std::clamp(static_cast<int>(flops / kFlopsPerBand), 2, kBands);
  }

  // s's descendants, in index order: the order of their updates' sums does not depend on when each was
  // linked, which depends on the threads.
  void collectDescendants(int s, std::vector<int>& out) const {
    out.clear();
    for (int d = head_[s]; d != -1; d = next_[d]) out.push_back(d);
    std::sort(out.begin(), out.end());
  }

  void link(int d, int ancestor) {
    next_[d] = head_[ancestor];
    head_[ancestor] = d;
  }

  // d into its ancestor's list when that is this thread's, else into the pending list.
  void pass(int d, int ancestor, Workspace& w, const std::vector<char>& mine) {
    if (mine[ancestor])
      link(d, ancestor);
    else
      w.pending.push_back(d);
  }

  // The columns of S (the lower triangle of P A P') that s holds, scattered into its zeroed block.
  void assembleMatrix(int s, const std::vector<int>& map, double* block) const {
    const int* Sp = S_.p.data();
    const int* Si = S_.i.data();
    const double* Sx = S_.x.data();
    const int k1 = sn_.first(s), nsrow = sn_.rows(s);
    for (int k = k1; k < k1 + sn_.cols(s); ++k) {
      double* column = block + static_cast<size_t>(k - k1) * nsrow;
      for (int p = Sp[k]; p < Sp[k + 1]; ++p) {
        const int row = map[Si[p]];
        if (Si[p] >= k && row >= 0 && row < nsrow) column[row] = Sx[p];
      }
    }
  }

  // s -= the update of descendant d (its rows from lpos[d] on, of which those below s's last column
  // continue to d's next ancestor); returns the position after d's rows in s's columns.
  int subtractUpdate(int s, int d, Workspace& w, double* block) const {
    const int k2 = sn_.first(s) + sn_.cols(s), nsrow = sn_.rows(s);
    const int ndrow = sn_.rows(d), ndcol = sn_.cols(d);
    const int pdi1 = sn_.pi[d] + lpos_[d], pdend = sn_.pi[d + 1];
    int pdi2 = pdi1;
    while (pdi2 < pdend && sn_.ls[pdi2] < k2) ++pdi2;
    const int ndrow1 = pdi2 - pdi1, ndrow2 = pdend - pdi1;
    const double* l1 = sn_.x + sn_.px[d] + lpos_[d];
    double* c = w.c.data();
    blas::syrkLower(ndrow1, ndcol, l1, ndrow, c, ndrow2);
    if (ndrow2 > ndrow1)
      blas::gemmNT(ndrow2 - ndrow1, ndrow1, ndcol, l1 + ndrow1, ndrow, l1, ndrow, c + ndrow1, ndrow2);
    int* rel = w.relativeMap.data();
    for (int i = 0; i < ndrow2; ++i) rel[i] = w.map[sn_.ls[pdi1 + i]];
    for (int j = 0; j < ndrow1; ++j) {
      double* column = block + static_cast<size_t>(rel[j]) * nsrow;
      const double* cj = c + static_cast<size_t>(j) * ndrow2;
      for (int i = j; i < ndrow2; ++i) column[rel[i]] -= cj[i];
    }
    return pdi2 - sn_.pi[d];
  }

  // The rows of d (from lpos[d] on) that lie in rows [r0, r1) of s: minus their products with d's rows in
  // s's columns, where below the diagonal.
  void subtractUpdateRows(int s, int d, const std::vector<int>& map, Workspace& w, double* block, int r0,
                          int r1) const {
    const int k2 = sn_.first(s) + sn_.cols(s), nsrow = sn_.rows(s);
    const int pdi1 = sn_.pi[d] + lpos_[d], ndrow2 = sn_.pi[d + 1] - pdi1;
    const int* rows = sn_.ls + pdi1;
    const int ndrow1 = static_cast<int>(std::lower_bound(rows, rows + ndrow2, k2) - rows);
    const auto below = [&](int target) {  // d's first row at or after position `target` of s
      return static_cast<int>(
          std::partition_point(rows, rows + ndrow2, [&](int row) { return map[row] < target; }) - rows);
    };
    const int lo = below(r0), hi = below(r1), jn = std::min(ndrow1, hi);
    if (lo >= hi || jn == 0) return;
    const double* l1 = sn_.x + sn_.px[d] + lpos_[d];
    double* c = w.c.data();
    blas::gemmNT(hi - lo, jn, sn_.cols(d), l1 + lo, sn_.rows(d), l1, sn_.rows(d), c, hi - lo);
    for (int j = 0; j < jn; ++j) {
      double* column = block + static_cast<size_t>(map[rows[j]]) * nsrow;
      const double* cj = c + static_cast<size_t>(j) * (hi - lo) - lo;
      for (int i = std::max(lo, j); i < hi; ++i) column[map[rows[i]]] -= cj[i];
    }
  }

  void failAt(int column) {
    int seen = failed_.load();
    while (column < seen && !failed_.compare_exchange_weak(seen, column)) {
    }
  }

  // factorOne's work in bandsOf(s) bands of s's rows: the descendants' updates band by band, then the dense
  // block (factorBlockInBands), on `parts` threads (spaces[0 .. parts - 1]; spaces[0] holds the maps).
  void factorBanded(int s, Workspace* spaces, int parts, const std::vector<char>& mine) {
    const int psi = sn_.pi[s], nscol = sn_.cols(s), nsrow = sn_.rows(s);
    const int k2 = sn_.first(s) + nscol;
    double* block = sn_.x + sn_.px[s];
    std::vector<int>& map = spaces[0].map;
    std::fill(block, block + static_cast<size_t>(nsrow) * nscol, 0.0);
    for (int k = 0; k < nsrow; ++k) map[sn_.ls[psi + k]] = k;
    assembleMatrix(s, map, block);
    std::vector<int>& descendants = spaces[0].descendants;
    collectDescendants(s, descendants);
    const int bands = bandsOf(s);
    int bounds[kBands + 1];
    // A row of s takes updates in its columns up to itself.
    splitRows(
        0, nsrow, bands, [&](int r) { return static_cast<double>(std::min(r + 1, nscol)); }, bounds);
    forBands(bands, parts, [&](int b, int k) {
      for (const int d : descendants)
        subtractUpdateRows(s, d, map, spaces[k], block, bounds[b], bounds[b + 1]);
    });
    for (const int d : descendants) {
      const int* rows = sn_.ls + sn_.pi[d];
      lpos_[d] = static_cast<int>(std::lower_bound(rows + lpos_[d], rows + sn_.rows(d), k2) - rows);
      if (lpos_[d] < sn_.rows(d)) pass(d, superMap_[rows[lpos_[d]]], spaces[0], mine);
    }
    head_[s] = -1;
    banded_.fetch_add(1, std::memory_order_relaxed);
    const int info = factorBlockInBands(block, nsrow, nscol, bands, parts);
    if (info != 0) return failAt(sn_.first(s) + info - 1);
    if (nsrow == nscol) return;
    lpos_[s] = nscol;
    pass(s, parent_[s], spaces[0], mine);
  }

  void factorOne(int s, Workspace& w, const std::vector<char>& mine) {
    const int psi = sn_.pi[s], nscol = sn_.cols(s), nsrow = sn_.rows(s);
    double* block = sn_.x + sn_.px[s];
    std::fill(block, block + static_cast<size_t>(nsrow) * nscol, 0.0);
    for (int k = 0; k < nsrow; ++k) w.map[sn_.ls[psi + k]] = k;
    assembleMatrix(s, w.map, block);
    collectDescendants(s, w.descendants);
    for (const int d : w.descendants) {
      lpos_[d] = subtractUpdate(s, d, w, block);
      if (lpos_[d] < sn_.rows(d)) pass(d, superMap_[sn_.ls[sn_.pi[d] + lpos_[d]]], w, mine);
    }
    head_[s] = -1;
    const int info = blas::potrfLower(nscol, block, nsrow);
    if (info != 0) return failAt(sn_.first(s) + info - 1);
    if (nsrow == nscol) return;
    blas::trsmRightLowerTransposed(nsrow - nscol, nscol, block, nsrow, block + nscol, nsrow);
    lpos_[s] = nscol;
    pass(s, parent_[s], w, mine);
  }

  Supernodes sn_;
  const PermutedTriangle& S_;
  std::vector<int> superMap_, head_, next_, lpos_, parent_;
  std::vector<int64_t> work_;
  std::atomic<int> failed_{sn_.n};
  std::atomic<int> banded_{0};
};

// The BLAS's first calls may set up state of its own (Eigen's cache sizes in wasm, whose objects are not
// built for threads): made on this thread before the helpers call it. Straight to the BLAS, since blocks
// this small would stay inline.
void touchDenseKernels() {
  double a[4] = {4, 2, 2, 4}, c[4] = {0, 0, 0, 0};
  const int one = 1, two = 2;
  const double alpha = 1, beta = 0;
  int info = 0;
  blas::dsyrk_("L", "N", &one, &one, &alpha, a, &two, &beta, c, &two);
  blas::dgemm_("N", "T", &one, &one, &one, &alpha, a, &two, a, &two, &beta, c, &two);
  blas::dpotrf_("L", &two, a, &two, &info);
  blas::dtrsm_("R", "L", "T", "N", &one, &one, &alpha, a, &two, c, &two);
}

bool factorSerially(cholmod_sparse& A, cholmod_factor& L, cholmod_common& c, SupernodalReport& report,
                    std::string why) {
  report.parts = 1;
  report.singleThreadWhy = std::move(why);
  return cholmod_factorize(&A, &L, &c) != 0;
}

// L numeric and marked LL', ready for the project's factorization; false where CHOLMOD could not allocate.
bool prepareNumeric(cholmod_factor& L, cholmod_common& c) {
  if (L.xtype == CHOLMOD_PATTERN && !cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, &L, &c)) return false;
  L.is_ll = 1;
  return true;
}

// The lower triangle of P A P' with values, for L's permutation P, unless the analysis handed it on.
PermutedTriangle permutedLower(const cholmod_sparse& A, const cholmod_factor& L, int parts,
                               PermutedTriangle* given) {
  if (given && !given->p.empty()) return std::exchange(*given, PermutedTriangle());
  std::vector<int> inverse(L.n);
  for (size_t k = 0; k < L.n; ++k) inverse[static_cast<const int*>(L.Perm)[k]] = static_cast<int>(k);
  return permutedTriangle(A, inverse, Triangle::Lower, true, parts);
}

// c.status and L.minor as cholmod_factorize leaves them.
bool finish(cholmod_factor& L, cholmod_common& c, const Factorization& f) {
  c.status = CHOLMOD_OK;
  L.minor = static_cast<size_t>(f.failedColumn());
  if (L.minor < L.n) c.status = CHOLMOD_NOT_POSDEF;
  return true;
}

// The project's factorization on this thread alone, every supernode after its descendants.
bool factorOnOneThread(cholmod_sparse& A, cholmod_factor& L, cholmod_common& c, SupernodalReport& report,
                       std::string why, PermutedTriangle* lower) {
  report = SupernodalReport();
  report.singleThreadWhy = std::move(why);
  if (!prepareNumeric(L, c)) return false;
  PermutedTriangle S = permutedLower(A, L, 1, lower);
  Factorization f(supernodesOf(L), S);
  std::vector<int> nodes(L.nsuper);
  std::iota(nodes.rbegin(), nodes.rend(), 0);
  const std::vector<char> mine(L.nsuper, 1);
  Workspace w;
  f.prepare(w, L.maxcsize);
  const blas::BlasOnCallingThread blasAlone;  // the calls the threads would make, made as they make them
  f.factorAll(nodes, w, mine);
  report.bandedSupernodes = f.bandedSupernodes();
  return finish(L, c, f);
}

// One thread's factorization of a supernodal L: the project's, the same operations as on any number of
// threads (and in wasm its dense kernels use the SIMD lanes, where CHOLMOD's would call Eigen's BLAS, one
// double at a time there); CHOLMOD's where a test asks for it.
bool factorSupernodalAlone(cholmod_sparse& A, cholmod_factor& L, cholmod_common& c, SupernodalReport& report,
                           std::string why, PermutedTriangle* lower) {
  if (ownFactorizationAlone.load()) return factorOnOneThread(A, L, c, report, std::move(why), lower);
  return factorSerially(A, L, c, report, std::move(why));
}

}  // namespace

void failNextSupernodalThreads() {
  failThreadsOnce = true;
}

bool setOwnFactorizationAlone(bool own) {
  return ownFactorizationAlone.exchange(own);
}

bool factorSupernodal(cholmod_sparse& A, cholmod_factor& L, int parts, cholmod_common& c,
                      SupernodalReport& report, PermutedTriangle* lower) {
  report = SupernodalReport();
  if (!L.is_super)
    return factorSerially(A, L, c, report,
                          parts <= 1 ? "" : "the factor is simplicial (too little fill to split)");
  if (parts <= 1) return factorSupernodalAlone(A, L, c, report, "", lower);
  ThreadTeam* team = nullptr;
  try {
    team = &ThreadTeam::shared();
  } catch (const std::exception& e) {
    return factorSupernodalAlone(A, L, c, report,
                                 std::string("the helper threads could not start: ") + e.what(), lower);
  }
  parts = std::min(parts, ThreadTeam::maxParts());
  if (!prepareNumeric(L, c)) return false;
  PermutedTriangle S;
  Factorization f(supernodesOf(L), S);
  const SubtreePartition partition = partitionSubtrees(f.parent(), f.work(), parts);
  if (partition.groups.size() < 2)
    return factorSupernodalAlone(A, L, c, report, "the elimination tree has no subtrees worth splitting",
                                 lower);
  const int groups = static_cast<int>(partition.groups.size());
  S = permutedLower(A, L, groups, lower);
  std::vector<Workspace> spaces(groups);
  std::vector<std::vector<char>> mine(groups + 1, std::vector<char>(L.nsuper, 0));
  for (int g = 0; g < groups; ++g)
    for (const int s : partition.groups[g]) mine[g][s] = 1;
  for (const int s : partition.top) mine[groups][s] = 1;
  touchDenseKernels();
  const blas::BlasOnCallingThread blasAlone;
  std::atomic<int> ran{0};
  const bool failing = failThreadsOnce.exchange(false);
  team->run(groups, [&](int g) {
    if (failing && g > 0) return;  // as a helper that never started
    f.prepare(spaces[g], L.maxcsize);
    f.factorAll(partition.groups[g], spaces[g], mine[g]);
    spaces[g].map = std::vector<int>();
    ran.fetch_add(1);
  });
  if (ran.load() < groups)
    return factorSupernodalAlone(A, L, c, report,
                                 "a helper thread did not run its part of the factorization (" +
                                     std::to_string(ran.load()) + " of " + std::to_string(groups) +
                                     " parts ran)",
                                 nullptr);
  for (Workspace& w : spaces) f.linkPending(w);
  // The top's bands on every thread asked for, also where the cut made fewer groups than threads.
  spaces.resize(parts);  // groups <= parts
  for (int g = 0; g < parts; ++g) f.prepare(spaces[g], L.maxcsize, g == 0);
  f.factorTop(partition.top, spaces, parts, mine[groups]);
  report.parts = parts;
  report.groups = groups;
  report.bandedSupernodes = f.bandedSupernodes();
  report.subtreeShare =
      1.0 - static_cast<double>(partition.topWork) / static_cast<double>(partition.totalWork);
  return finish(L, c, f);
}

}  // namespace tvf
