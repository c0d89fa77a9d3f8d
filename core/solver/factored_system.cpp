#include "solver/factored_system.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "common/input_error.h"
#include "common/stopwatch.h"
#include "common/thread_team.h"
#include "solver/backward_substitution.h"
#include "solver/cholmod_handles.h"
#include "solver/edge_dissection.h"
#include "solver/factor_memory.h"
#include "solver/forward_solution.h"
#include "solver/ldl_conversion.h"
#include "solver/supernodal_cholesky.h"
#include "solver/symbolic_analysis.h"
#include "solver/woodbury_correction.h"

namespace tvf {
namespace {

// Exactly one ordering: CHOLMOD's default (nmethods = 0) tries AMD, then METIS when AMD's fill looks high,
// and keeps the better; an interactive session pays for one.
void chooseOrdering(cholmod_common& c, FillOrdering ordering) {
  c.nmethods = 1;
  c.postorder = 1;  // the weighted postorder the supernodal analysis computes anyway, folded into Perm
  if (ordering == FillOrdering::Amd) {
    c.method[0].ordering = CHOLMOD_AMD;
    return;
  }
  // With the mesh at hand the METIS ordering dissects its vertex graph instead (Impl::dissectionOrdering);
  // this is for a bare matrix, or a pattern those separators do not separate.
  c.method[0].ordering = CHOLMOD_NESDIS;
  // Nested dissection by METIS's vertex separators down to subgraphs of this size, then one constrained
  // minimum-degree ordering (CAMD) of the whole matrix that keeps the separators last (CHOLMOD's method 5).
  // On bunny00 METIS_NodeND on the whole graph costs 5-7x AMD's analysis, and NESDIS to CHOLMOD's default 200
  // more; stopping the recursion here keeps most of the fill reduction for a fraction of the time (README).
  c.method[0].nd_small = 20000;
  c.method[0].nd_camd = 1;  // (METIS's memory probe is off in every CholmodCommon: cholmod_handles.h)
}

// Parts of the mesh's dissection with at most this many edges are left to CAMD whole. The vertex graph's cuts
// are cheap enough to go this deep (bunny00: analysis ~2x AMD's, fill 51.2 nnz/row against 53.9 for CHOLMOD's
// NESDIS to 20000-edge leaves at ~3x, 58.6 for AMD; README).
constexpr int32_t kDissectionLeafEdges = 1000;

// The least room for a held update's G (solver/woodbury_correction.h), in doubles: 8 MB.
constexpr size_t kLeastHeldDoubles = size_t{1} << 20;

// A 64-bit FNV-1a hash of a sparse pattern, with its size: what decides whether the saved analysis fits the
// next matrix (a copy of the pattern to compare with took 36 MB at 1.25M edges).
uint64_t patternHash(const cholmod_sparse& A) {
  const int* Ap = static_cast<const int*>(A.p);
  const int* Ai = static_cast<const int*>(A.i);
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](uint64_t v) {
    for (int k = 0; k < 4; ++k, v >>= 8) h = (h ^ (v & 0xff)) * 1099511628211ull;
  };
  mix(A.ncol);
  for (size_t j = 0; j <= A.ncol; ++j) mix(static_cast<uint32_t>(Ap[j]));
  for (int k = 0; k < Ap[A.ncol]; ++k) mix(static_cast<uint32_t>(Ai[k]));
  return h;
}

// upper's values with diagonal[j] added to each column's last entry, which must be its diagonal; empty when
// a diagonal entry is missing from the pattern.
std::vector<double> valuesPlusDiagonal(const SparseMatrix& upper, const std::vector<double>& diagonal) {
  const int* p = upper.outerIndexPtr();
  const int* i = upper.innerIndexPtr();
  std::vector<double> values(upper.valuePtr(), upper.valuePtr() + upper.nonZeros());
  for (int j = 0; j < upper.outerSize(); ++j) {
    if (p[j + 1] == p[j] || i[p[j + 1] - 1] != j) return {};
    values[p[j + 1] - 1] += diagonal[j];
  }
  return values;
}

// Peak memory of factor() from the symbolic analysis: the supernodal values (xsize doubles) live together
// with the row indices the conversion to the simplicial LDL' allocates (at most xsize ints; the values are
// converted in place), plus per column CHOLMOD's workspace (~92 bytes) and the updates' (8 doubles).
double peakFactorBytes(const cholmod_factor& L, double lnz) {
  const double n = static_cast<double>(L.n);
  const double factor = 12.0 * (L.is_super ? static_cast<double>(L.xsize) : lnz);
  return factor + (92.0 + 64.0) * n;
}

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f GB", bytes / 1e9);
  return text;
}

}  // namespace

struct FactoredSystem::Impl {
  FillOrdering ordering;
  CholmodCommon common;
  CholmodFactorPtr factor{nullptr, {common.get()}};
  CholmodDensePtr solution{nullptr, {common.get()}};
  // Workspace reused across solves so that a solve allocates nothing.
  cholmod_dense* ySolve = nullptr;
  cholmod_dense* eSolve = nullptr;
  cholmod_dense* forwardFull = nullptr;
  // L^-1 P b of the last tracked solve, redone after an edit only on the columns the edit changed.
  ForwardSolution forward;
  int threads = ThreadTeam::usefulParts();
  int factorThreads = threads;
  BackwardKernel backwardKernel = kDefaultBackwardKernel;
  BackwardSubstitution backward;
  int64_t supernodalSolves = 0;
  std::vector<double> bPermuted, xPermuted;  // scratch: what solve() keeps is in `forward`
  FactorTimings timings;
  std::vector<int> inversePerm;
  bool wasSupernodal = false;
  int n = 0;
  // The fill-reducing ordering of the last factored matrix and a hash of that matrix's pattern: a boundary or
  // gamma change that keeps the pattern is refactored without ordering again. Only the permutation is kept,
  // not the symbolic factor (its supernodes' row indices: 35 MB at 1.25M edges, at the memory peak), unless
  // asked for (keepSymbolic: for a cache beyond this system) or adopted (for the next factorization alone).
  std::vector<int> orderingPerm;
  uint64_t orderingPattern = 0;
  KeptSymbolic symbolic;
  bool keepSymbolic = false;
  std::vector<int> updateOrder;  // update columns by position in L (see sortColumns)
  // The update columns of the last edit: positions in L, ascending, and weights.
  std::vector<int> positions;
  std::vector<double> weights;
  // An update held beside the factor (deferUpdate) until applyDeferred; its G lies in CHOLMOD's update
  // workspace (Common->Xwork), which cholmod_updown would allocate anyway.
  WoodburyCorrection deferred;
  double memoryLimit = 0, estimatedBytes = 0;
  std::vector<int32_t> edgeVertices;
  int32_t numVertices = 0;
  bool usedDissection = false;  // the mesh's dissection ordered the last analysis
  PermutedTriangle lower;       // the analysis's P A P', until the factorization takes it

  explicit Impl(FillOrdering o) : ordering(o) {
    factor_memory::install();
    backward.setParts(threads);
    chooseOrdering(*common.get(), o);
    common->supernodal = CHOLMOD_AUTO;
    // No relaxed amalgamation of supernodes, not even of the smallest (CHOLMOD merges those of up to 4
    // columns whatever their zeros): the explicit zeros it adds (30 % of the values at 1.25M edges) sit in
    // the supernodal factor beside the row indices the conversion to LDL' allocates, the memory peak, and a
    // resymbol would have to drop them after it (bunny00 natively: 19 ms to drop 1.1 % of the values). The
    // supernodes are then fundamental, their pattern L's exact one, and the factorization is no slower
    // (docs/method.md).
    std::fill(std::begin(common->zrelax), std::end(common->zrelax), 0.0);
    std::fill(std::begin(common->nrelax), std::end(common->nrelax), 0);
    common->final_asis = 1;
    // Updates take the columns two at a time: their workspace is maxrank columns of n doubles, which for
    // CHOLMOD's default 8 (80 MB at 1.25M edges) found no room left after the conversion and grew the heap to
    // 1.87 GB; at 2 it peaks at 1.79 GB (bench:web). A stroke's update measured 122-140 ms at 8, 134-161 ms
    // at 2 in the page on this noisy 2-core machine.
    common->maxrank = 2;
    common->print = 0;
    common->error_handler = nullptr;
  }
  ~Impl() {
    cholmod_free_dense(&ySolve, common.get());
    cholmod_free_dense(&eSolve, common.get());
    cholmod_free_dense(&forwardFull, common.get());
  }

  static cholmod_dense columnView(const double* values, size_t n) {
    cholmod_dense d{};
    d.nrow = n;
    d.ncol = 1;
    d.nzmax = n;
    d.d = n;
    d.x = const_cast<double*>(values);
    d.xtype = CHOLMOD_REAL;
    d.dtype = CHOLMOD_DOUBLE;
    return d;
  }

  // sys (CHOLMOD_A, _L, _DLt) applied to rhs, into `solution`.
  const double* solveSystem(int sys, const double* rhs, CholmodDensePtr& into) {
    cholmod_dense view = columnView(rhs, static_cast<size_t>(n));
    cholmod_dense* out = into.release();
    cholmod_solve2(sys, factor.get(), &view, nullptr, &out, nullptr, &ySolve, &eSolve, common.get());
    into.reset(out);
    if (!out) throw std::runtime_error("CHOLMOD solve failed");
    return static_cast<const double*>(out->x);
  }

  // P b and its inverse: L factors P A P'.
  void permute(const Eigen::VectorXd& b, std::vector<double>& into) const {
    const int* perm = static_cast<const int*>(factor->Perm);
    into.resize(n);
    for (int k = 0; k < n; ++k) into[k] = b[perm[k]];
  }
  void unpermute(const double* z, Eigen::VectorXd& x) const {
    const int* perm = static_cast<const int*>(factor->Perm);
    x.resize(n);
    for (int k = 0; k < n; ++k) x[perm[k]] = z[k];
  }

  // The supernodes are read from a simplicial LDL' factor's columns, which factor() leaves after every
  // successful factorization.
  bool bySupernodes() const {
    return backwardKernel == BackwardKernel::Supernodes && !factor->is_super && !factor->is_ll;
  }

  // L^-1 bPermuted in full (CHOLMOD), into forwardFull, which is the caller's to change until the next call.
  double* substituteForward() {
    CholmodDensePtr full(std::exchange(forwardFull, nullptr), {common.get()});
    solveSystem(CHOLMOD_L, bPermuted.data(), full);
    forwardFull = full.release();
    return static_cast<double*>(forwardFull->x);
  }

  // L^-T D^-1 y by supernodes, into xPermuted.
  const double* substituteBackwardBySupernodes(const double* y) {
    ++supernodalSolves;
    xPermuted.resize(n);
    backward.solve(*factor, y, xPermuted.data());
    return xPermuted.data();
  }

  // L^-T D^-1 y.
  const double* substituteBackward(const double* y) {
    if (!bySupernodes()) return solveSystem(CHOLMOD_DLt, y, solution);
    return substituteBackwardBySupernodes(y);
  }

  // L^-T D^-1 of y corrected for the held update. y stays as it is: the forward substitution kept is the
  // factor's, without the update. By supernodes the copy the backward substitution works in is corrected in
  // place; CHOLMOD's takes a corrected copy where P b was, which the forward substitution no longer needs.
  const double* substituteBackwardCorrected(const double* y) {
    if (!bySupernodes()) {
      std::copy(y, y + n, bPermuted.begin());
      deferred.correct(*factor, bPermuted.data());
      return solveSystem(CHOLMOD_DLt, bPermuted.data(), solution);
    }
    ++supernodalSolves;
    xPermuted.assign(y, y + n);
    deferred.correct(*factor, xPermuted.data());
    backward.solve(*factor, xPermuted.data(), xPermuted.data());
    return xPermuted.data();
  }

  // The update columns sqrt(w) e_row into `positions` and `weights`. L factors P A P', so each enters at the
  // permuted position of its row. Columns go in the order of those positions: cholmod_updown takes them a
  // few at a time (Common->maxrank), and columns close in the postordered elimination tree share most of
  // their path to the root, which each group walks once.
  void sortColumns(const std::vector<int32_t>& rows, const std::vector<double>& w) {
    const int k = static_cast<int>(rows.size());
    updateOrder.resize(k);
    std::iota(updateOrder.begin(), updateOrder.end(), 0);
    std::sort(updateOrder.begin(), updateOrder.end(),
              [&](int a, int b) { return inversePerm[rows[a]] < inversePerm[rows[b]]; });
    positions.resize(k);
    weights.resize(k);
    for (int c = 0; c < k; ++c) {
      positions[c] = inversePerm[rows[updateOrder[c]]];
      weights[c] = w[updateOrder[c]];
    }
  }

  // L L' +/- the columns in `positions` and `weights`, in one cholmod_updown call.
  void updown(bool downdate) {
    const int k = static_cast<int>(positions.size());
    CholmodSparsePtr C(cholmod_allocate_sparse(n, k, k, 1, 1, 0, CHOLMOD_REAL, common.get()), {common.get()});
    if (!C) throw std::runtime_error("CHOLMOD could not allocate an update");
    int* p = static_cast<int*>(C->p);
    int* i = static_cast<int*>(C->i);
    double* x = static_cast<double*>(C->x);
    for (int c = 0; c < k; ++c) {
      p[c] = c;
      i[c] = positions[c];
      x[c] = std::sqrt(weights[c]);
    }
    p[k] = k;
    forward.beforeUpdate(*factor, i, k);
    if (!cholmod_updown(downdate ? 0 : 1, C.get(), factor.get(), common.get())) {
      forward.invalidate();
      throw std::runtime_error("CHOLMOD update/downdate failed");
    }
  }

  // Into the factor: the update held beside it.
  void applyDeferred() {
    if (deferred.empty()) return;
    deferred.clear();  // zeroes the workspace cholmod_updown is about to take
    updown(false);
  }

  // The symbolic factor of A, ordered by the kept permutation when A's pattern is unchanged, else by a new
  // ordering (which is kept).
  cholmod_factor* analyzeOrReuse(cholmod_sparse& A, const SparseMatrix& upper) {
    const uint64_t pattern = patternHash(A);
    timings.analysisReused = orderingPerm.size() == A.ncol && pattern == orderingPattern;
    timings.symbolicReused = false;
    cholmod_factor* L = nullptr;
    if (timings.analysisReused && !symbolic.empty()) {
      L = symbolicFromKept(A, orderingPerm, symbolic, factorThreads, *common.get(), lower);
      timings.symbolicReused = L != nullptr;
    }
    if (!L) L = timings.analysisReused ? analyzeGiven(A, orderingPerm) : analyze(A, upper);
    if (!L) return nullptr;
    const int* perm = static_cast<const int*>(L->Perm);
    orderingPerm.assign(perm, perm + L->n);
    orderingPattern = pattern;
    // An adopted symbolic factor served this factorization alone, unless one is kept for a cache: then it is
    // this factorization's, adopted or analyzed.
    if (!keepSymbolic)
      symbolic = KeptSymbolic();
    else if (!timings.symbolicReused)
      symbolic = keptSymbolicOf(*L);
    return L;
  }

  // What cholmod_analyze_p makes of a given ordering (symbolic_analysis.h), with the permuted lower triangle
  // kept for the factorization.
  cholmod_factor* analyzeGiven(cholmod_sparse& A, const std::vector<int>& perm) {
    return analyzeOrdering(A, perm, factorThreads, *common.get(), lower);
  }

  // Nested dissection of the mesh's vertex graph (edge cuts, widened where A couples edges further apart),
  // then one CAMD ordering that keeps each separator after the parts it separates: CHOLMOD's NESDIS, on a
  // graph a third the size. Empty when there is no mesh, or (never seen) when the separators do not separate
  // A.
  std::vector<int> dissectionOrdering(cholmod_sparse& A, const SparseMatrix& upper) {
    const int32_t n = static_cast<int32_t>(A.ncol);
    if (ordering != FillOrdering::Metis || static_cast<int32_t>(edgeVertices.size()) != 2 * n) return {};
    const auto start = std::chrono::steady_clock::now();
    EdgeDissection d = dissectEdges(edgeVertices, numVertices, kDissectionLeafEdges, upper, factorThreads);
    timings.dissectionMs = msSince(start);
    if (!separatesPattern(d, upper)) return {};
    std::vector<int> perm(n);
    if (!cholmod_camd(&A, nullptr, 0, d.constraintSet.data(), perm.data(), common.get())) return {};
    usedDissection = true;
    return perm;
  }

  // upper: A's upper triangle, whose pattern the dissection must respect.
  cholmod_factor* analyze(cholmod_sparse& A, const SparseMatrix& upper) {
    usedDissection = false;
    std::vector<int> perm = dissectionOrdering(A, upper);
    if (perm.empty()) return cholmod_analyze(&A, common.get());
    return analyzeGiven(A, perm);
  }
};

FactoredSystem::FactoredSystem(FillOrdering ordering) : impl_(std::make_unique<Impl>(ordering)) {}
FactoredSystem::~FactoredSystem() = default;
FactoredSystem::FactoredSystem(FactoredSystem&&) noexcept = default;
FactoredSystem& FactoredSystem::operator=(FactoredSystem&&) noexcept = default;

bool FactoredSystem::factor(const SparseMatrix& A) {
  return factorUpper(upperTriangle(A), {});
}

bool FactoredSystem::factorUpper(const SparseMatrix& upper, const std::vector<double>& diagonal) {
  Impl& s = *impl_;
  // Once made, or refused: the blocks the factor let go last, kept for this one (factor_memory.h), and the
  // analysis's triangle are no longer wanted.
  const struct Done {
    Impl& s;
    ~Done() {
      s.lower = PermutedTriangle();
      factor_memory::releaseKept();
    }
  } done{s};
  s.deferred.clear();  // the matrix given holds whatever was deferred
  s.factor.reset();    // the previous factor goes before the new one is made
  s.n = static_cast<int>(upper.rows());
  std::vector<double> values;
  if (!diagonal.empty()) {
    values = valuesPlusDiagonal(upper, diagonal);
    if (values.empty()) {  // a diagonal entry the pattern lacks: only then is the matrix copied whole
      SparseMatrix D(upper.rows(), upper.cols());
      D.reserve(Eigen::VectorXi::Constant(upper.cols(), 1));
      for (int j = 0; j < upper.cols(); ++j) D.insert(j, j) = diagonal[j];
      return factorUpper(upperTriangle(upper + D), {});
    }
  }
  cholmod_sparse view = upperTriangleView(upper);
  if (!values.empty()) view.x = values.data();
  auto start = std::chrono::steady_clock::now();
  s.timings.dissectionMs = 0;
  s.forward.invalidate();
  s.backward.invalidate();
  std::vector<double>().swap(s.bPermuted);
  std::vector<double>().swap(s.xPermuted);
  cholmod_free_dense(&s.forwardFull, s.common.get());
  s.factor.reset(s.analyzeOrReuse(view, upper));
  if (!s.factor) throw std::runtime_error("CHOLMOD analysis failed (out of memory?)");
  s.timings.analyzeMs = msSince(start);
  s.wasSupernodal = s.factor->is_super;
  s.estimatedBytes = peakFactorBytes(*s.factor, s.common->lnz);
  if (s.memoryLimit > 0 && s.estimatedBytes > s.memoryLimit) {
    s.factor.reset();
    throw InputError("the mesh is too large to design on here: factoring its " + std::to_string(s.n) +
                     "-edge system needs about " + gigabytes(s.estimatedBytes) +
                     " of memory, more than the " + gigabytes(s.memoryLimit) + " available");
  }
  start = std::chrono::steady_clock::now();
  SupernodalReport threading;
  factorSupernodal(view, *s.factor, s.factorThreads, *s.common.get(), threading, &s.lower);
  s.lower = PermutedTriangle();  // already, before the conversion's peak
  s.timings.factorMs = msSince(start);
  s.timings.factorThreads = threading.parts;
  s.timings.factorGroups = threading.groups;
  s.timings.singleThreadWhy = threading.singleThreadWhy;
  s.timings.subtreeShare = threading.subtreeShare;
  s.timings.bandedSupernodes = threading.bandedSupernodes;
  if (s.common->status == CHOLMOD_OUT_OF_MEMORY) {
    s.factor.reset();
    throw InputError("out of memory while factoring the " + std::to_string(s.n) + "-edge system (estimated " +
                     gigabytes(s.estimatedBytes) + ")");
  }
  // The values copy goes before the conversion's peak.
  std::vector<double>().swap(values);
  view.x = const_cast<double*>(upper.valuePtr());
  const bool ok = s.common->status == CHOLMOD_OK && s.factor->minor == s.factor->n;
  // Updates need the simplicial LDL' form; converting once here keeps every later edit a pure update.
  start = std::chrono::steady_clock::now();
  if (ok) {
    convertToSimplicialLdl(*s.factor, *s.common.get(), threading.parts);
    if (s.bySupernodes()) s.backward.prepare(*s.factor);
  }
  // The factorization's workspace (the supernodal update matrices among it) would stay in the common object.
  // The updates' workspace (maxrank columns of n doubles, see Impl) is allocated by the first update: by then
  // the room the conversion freed has its place (measured at 1.25M edges with 8 columns: the wasm heap peaked
  // at 1.87 GB, where allocating it here, ahead of the first field's read-outs, left it at 1.97 GB).
  cholmod_free_work(s.common.get());
  s.timings.convertMs = msSince(start);
  const int* perm = static_cast<const int*>(s.factor->Perm);
  s.inversePerm.resize(s.n);
  for (int k = 0; k < s.n; ++k) s.inversePerm[perm[k]] = k;
  return ok;
}

void FactoredSystem::updateDiagonal(const std::vector<int32_t>& rows, const std::vector<double>& weights,
                                    bool downdate) {
  Impl& s = *impl_;
  if (rows.empty()) return;
  s.applyDeferred();
  s.sortColumns(rows, weights);
  s.updown(downdate);
}

bool FactoredSystem::deferUpdate(const std::vector<int32_t>& rows, const std::vector<double>& weights) {
  Impl& s = *impl_;
  if (rows.empty()) return true;
  s.applyDeferred();
  s.sortColumns(rows, weights);
  // G goes where cholmod_updown keeps its workspace (maxrank columns of n doubles, and n ints of which the
  // correction borrows the slots of Q), allocated here as the update would: the wasm heap does not grow
  // for it (see Impl).
  const size_t n = static_cast<size_t>(s.n);
  cholmod_common& c = *s.common.get();
  // On a small mesh the paths to the root are most of the columns, and a stroke of an N-direction field has
  // two columns a face: G gets at least kLeastHeldDoubles there (the updates' own workspace is larger on a
  // mesh past half a million unknowns).
  const size_t xwork = std::max(static_cast<size_t>(c.maxrank) * n, kLeastHeldDoubles);
  const bool room = cholmod_allocate_work(n, n, xwork, &c) && c.status == CHOLMOD_OK;
  if (room && s.deferred.prepare(*s.factor, s.positions.data(), s.weights.data(),
                                 static_cast<int>(s.positions.size()), static_cast<double*>(c.Xwork),
                                 c.xworksize, static_cast<int*>(c.Iwork), s.threads))
    return true;
  s.updown(false);
  return false;
}

void FactoredSystem::applyDeferred() {
  impl_->applyDeferred();
}

bool FactoredSystem::hasDeferred() const {
  return !impl_->deferred.empty();
}

void FactoredSystem::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& s = *impl_;
  s.permute(b, s.bPermuted);
  if (!s.forward.substituteIncrementally(*s.factor, s.bPermuted.data()))
    s.forward.setFull(s.bPermuted.data(), s.substituteForward(), s.n);
  if (s.deferred.empty()) return s.unpermute(s.substituteBackward(s.forward.y().data()), x);
  s.unpermute(s.substituteBackwardCorrected(s.forward.y().data()), x);
}

void FactoredSystem::solveOnce(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& s = *impl_;
  if (!s.bySupernodes() && s.deferred.empty()) {
    const double* z = s.solveSystem(CHOLMOD_A, b.data(), s.solution);
    x = Eigen::Map<const Eigen::VectorXd>(z, b.size());
    return;
  }
  s.permute(b, s.bPermuted);
  double* y = s.substituteForward();
  if (!s.deferred.empty()) s.deferred.correct(*s.factor, y);
  s.unpermute(s.substituteBackward(y), x);
}

int64_t FactoredSystem::incrementalSolves() const {
  return impl_->forward.incrementalCount();
}

int64_t FactoredSystem::supernodalSolves() const {
  return impl_->supernodalSolves;
}

void FactoredSystem::setOrdering(FillOrdering ordering) {
  auto next = std::make_unique<Impl>(ordering);
  next->edgeVertices = std::move(impl_->edgeVertices);
  next->numVertices = impl_->numVertices;
  next->memoryLimit = impl_->memoryLimit;
  next->backwardKernel = impl_->backwardKernel;
  next->threads = impl_->threads;
  next->factorThreads = impl_->factorThreads;
  next->keepSymbolic = impl_->keepSymbolic;
  next->backward.setParts(next->threads);
  impl_ = std::move(next);
}

KeptOrdering FactoredSystem::keptOrdering() const {
  KeptOrdering k;
  k.perm.assign(impl_->orderingPerm.begin(), impl_->orderingPerm.end());
  k.pattern = impl_->orderingPattern;
  k.ordering = impl_->ordering;
  k.dissection = impl_->usedDissection;
  if (impl_->keepSymbolic) k.symbolic = impl_->symbolic;
  return k;
}

bool FactoredSystem::adoptOrdering(KeptOrdering kept) {
  if (kept.ordering != impl_->ordering || kept.perm.empty()) return false;
  const size_t n = kept.perm.size();
  std::vector<uint8_t> seen(n, 0);
  for (int32_t p : kept.perm) {
    if (p < 0 || static_cast<size_t>(p) >= n || seen[p]) return false;
    seen[p] = 1;
  }
  impl_->orderingPerm = std::move(kept.perm);
  impl_->orderingPattern = kept.pattern;
  impl_->usedDissection = kept.dissection;
  impl_->symbolic = std::move(kept.symbolic);
  return true;
}

bool FactoredSystem::keptOrderingIsNew() const {
  const Impl& s = *impl_;
  if (s.orderingPerm.empty()) return false;
  if (!s.timings.analysisReused) return true;
  return !s.timings.symbolicReused && s.keepSymbolic && !s.symbolic.empty();
}

void FactoredSystem::setKeepSymbolic(bool keep) {
  impl_->keepSymbolic = keep;
  if (!keep) impl_->symbolic = KeptSymbolic();
}

void FactoredSystem::setEdgeGraph(std::vector<int32_t> edgeVertices, int32_t numVertices) {
  impl_->edgeVertices = std::move(edgeVertices);
  impl_->numVertices = numVertices;
  impl_->orderingPerm.clear();
  impl_->symbolic = KeptSymbolic();
}

void FactoredSystem::setFactorThreads(int threads) {
  impl_->factorThreads = std::clamp(threads, 1, ThreadTeam::maxParts());
}

void FactoredSystem::setThreads(int threads) {
  impl_->threads = std::clamp(threads, 1, ThreadTeam::maxParts());
  impl_->factorThreads = impl_->threads;
  impl_->backward.setParts(impl_->threads);
}

int FactoredSystem::threads() const {
  return impl_->threads;
}

void FactoredSystem::setBackwardKernel(BackwardKernel kernel) {
  impl_->backwardKernel = kernel;
}

void FactoredSystem::setMemoryLimit(double bytes) {
  impl_->memoryLimit = bytes;
}

double FactoredSystem::estimatedBytes() const {
  return impl_->estimatedBytes;
}

bool FactoredSystem::factored() const {
  return impl_->factor != nullptr;
}

void FactoredSystem::release() {
  Impl& s = *impl_;
  s.deferred.clear();
  s.factor.reset();
  s.forward = ForwardSolution();
  s.backward = BackwardSubstitution();
  s.backward.setParts(s.threads);
  cholmod_free_work(s.common.get());
}

int64_t FactoredSystem::factorNonzeros() const {
  const cholmod_factor* L = impl_->factor.get();
  if (!L) return 0;
  if (L->is_super) return static_cast<int64_t>(L->xsize);
  const int* colCount = static_cast<const int*>(L->nz);
  int64_t nnz = 0;
  for (size_t j = 0; j < L->n; ++j) nnz += colCount[j];
  return nnz;
}

const FactorTimings& FactoredSystem::timings() const {
  return impl_->timings;
}

std::string FactoredSystem::description() const {
  const Impl& s = *impl_;
  std::string backward;
  if (s.backwardKernel == BackwardKernel::Supernodes) {
    const size_t groups = s.backward.partition().groups.size();
    backward = ", backward substitution by supernodes";
    if (groups > 1) backward += " on " + std::to_string(groups) + " threads";
  }
  std::string threading;
  if (s.timings.factorThreads > 1)
    threading = " on " + std::to_string(s.timings.factorThreads) + " threads (" +
                std::to_string(static_cast<int>(100 * s.timings.subtreeShare + 0.5)) + " % of its work in " +
                (s.timings.factorGroups < s.timings.factorThreads
                     ? std::to_string(s.timings.factorGroups) + " groups of subtrees)"
                     : "subtrees)");
  else if (!s.timings.singleThreadWhy.empty())
    threading = " on one thread (" + s.timings.singleThreadWhy + ")";
  return std::string(s.wasSupernodal ? "supernodal LL'" : "simplicial LDL'") + threading +
         " factor, kept as simplicial LDL' for updates (" +
         (s.ordering == FillOrdering::Amd ? "AMD ordering)"
          : s.usedDissection              ? "METIS nested dissection of the mesh's vertex graph)"
                                          : "METIS nested dissection ordering)") +
         backward;
}

}  // namespace tvf
