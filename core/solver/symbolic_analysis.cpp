#include "solver/symbolic_analysis.h"

#include <cholmod_supernodal.h>

#include <algorithm>

namespace tvf {
namespace {

bool invert(const std::vector<int>& perm, std::vector<int>& inverse) {
  const int n = static_cast<int>(perm.size());
  inverse.assign(n, -1);
  for (int k = 0; k < n; ++k) {
    if (perm[k] < 0 || perm[k] >= n || inverse[perm[k]] >= 0) return false;
    inverse[perm[k]] = k;
  }
  return true;
}

// The tree, its column counts and the ordering relabelled by the postorder `post` (new k is old post[k]), as
// cholmod_analyze_p2 folds its weighted postorder in.
void relabel(const std::vector<int>& post, std::vector<int>& perm, std::vector<int>& parent,
             std::vector<int>& colCount) {
  const int n = static_cast<int>(post.size());
  std::vector<int> newOf(n), scratch(n);
  for (int k = 0; k < n; ++k) newOf[post[k]] = k;
  for (int k = 0; k < n; ++k) scratch[k] = perm[post[k]];
  perm.swap(scratch);
  for (int k = 0; k < n; ++k) scratch[k] = colCount[post[k]];
  colCount.swap(scratch);
  for (int k = 0; k < n; ++k) {
    const int old = parent[post[k]];
    scratch[k] = old < 0 ? -1 : newOf[old];
  }
  parent.swap(scratch);
}

bool isIdentity(const std::vector<int>& post) {
  for (size_t k = 0; k < post.size(); ++k)
    if (post[k] != static_cast<int>(k)) return false;
  return true;
}

bool supernodal(const cholmod_common& c) {
  return c.supernodal > CHOLMOD_AUTO ||
         (c.supernodal == CHOLMOD_AUTO && c.lnz > 0 && c.fl / c.lnz >= c.supernodal_switch);
}

}  // namespace

cholmod_factor* analyzeOrdering(const cholmod_sparse& A, std::vector<int> perm, int parts, cholmod_common& c,
                                PermutedTriangle& lower) {
  const int n = static_cast<int>(A.ncol);
  std::vector<int> inverse;
  lower = PermutedTriangle();
  if (static_cast<int>(perm.size()) != n || !invert(perm, inverse)) return nullptr;
  // The upper pattern S of P A P' (the tree, the supernodes' rows) and its lower triangle F with values (the
  // counts, then the factorization), for the ordering as it stands; the old ones go first.
  PermutedTriangle upper;
  cholmod_sparse S, F;
  const auto permute = [&] {
    upper = PermutedTriangle();
    lower = PermutedTriangle();
    upper = permutedTriangle(A, inverse, Triangle::Upper, false, parts);
    lower = permutedTriangle(A, inverse, Triangle::Lower, true, parts);
    S = patternView(upper, Triangle::Upper);
    F = patternView(lower, Triangle::Lower);
  };
  permute();
  std::vector<int> parent(n), post(n), colCount(n), first(n), level(n);
  if (!cholmod_etree(&S, parent.data(), &c) ||
      cholmod_postorder(parent.data(), n, nullptr, post.data(), &c) != n ||
      !cholmod_rowcolcounts(&F, nullptr, 0, parent.data(), post.data(), nullptr, colCount.data(),
                            first.data(), level.data(), &c))
    return nullptr;
  // The weighted postorder puts each supernode's columns together. An ordering kept from an earlier analysis
  // already is in it, and its triangles stand.
  if (c.postorder) {
    if (cholmod_postorder(parent.data(), n, colCount.data(), post.data(), &c) != n) return nullptr;
    if (!isIdentity(post)) {
      relabel(post, perm, parent, colCount);
      invert(perm, inverse);
      permute();
    }
  }
  cholmod_factor* L = cholmod_allocate_factor(n, &c);
  if (!L) return nullptr;
  std::copy(perm.begin(), perm.end(), static_cast<int*>(L->Perm));
  std::copy(colCount.begin(), colCount.end(), static_cast<int*>(L->ColCount));
  L->ordering = CHOLMOD_GIVEN;
  if (!supernodal(c)) {
    lower = PermutedTriangle();
    return L;
  }
  if (!cholmod_super_symbolic2(CHOLMOD_ANALYZE_FOR_CHOLESKY, &S, &F, parent.data(), L, &c)) {
    cholmod_free_factor(&L, &c);
    return nullptr;
  }
  return L;
}

namespace {

// The shapes and ranges of a supernodal factor's columns and rows for n columns: supernodes of increasing
// first columns covering 0 .. n-1, each with at least its own columns as rows, those first and in order,
// then rows below them, increasing.
bool wellFormed(const KeptSymbolic& k, int n) {
  const size_t count = k.super.size();
  if (count < 2 || k.pi.size() != count || k.super.front() != 0 || k.super.back() != n || k.pi.front() != 0 ||
      static_cast<size_t>(k.pi.back()) != k.s.size())
    return false;
  for (size_t t = 0; t + 1 < count; ++t) {
    const int first = k.super[t], end = k.super[t + 1], rows = k.pi[t + 1] - k.pi[t];
    if (end <= first || rows < end - first) return false;
    const int32_t* r = &k.s[k.pi[t]];
    for (int c = 0; c < end - first; ++c)
      if (r[c] != first + c) return false;
    for (int c = end - first; c < rows; ++c)
      if (r[c] <= r[c - 1] || r[c] >= n) return false;
  }
  return true;
}

// Each column's supernode, and each supernode's parent (the supernode of its first row below its own columns,
// a later one in a well-formed pattern; -1 for a root).
void supernodeTree(const KeptSymbolic& k, int n, std::vector<int>& of, std::vector<int>& parent) {
  const int count = static_cast<int>(k.super.size()) - 1;
  of.resize(n);
  for (int t = 0; t < count; ++t) std::fill(of.begin() + k.super[t], of.begin() + k.super[t + 1], t);
  parent.assign(count, -1);
  for (int t = 0; t < count; ++t) {
    const int below = k.pi[t] + k.super[t + 1] - k.super[t];
    if (below < k.pi[t + 1]) parent[t] = of[k.s[below]];
  }
}

// Every entry of the lower triangle F of P A P' lies in its column's supernode's rows, and every supernode's
// rows below its columns lie in its parent's rows: then the numeric factorization's scatters stay in the
// pattern and it holds L's.
bool holdsTheFactor(const KeptSymbolic& k, const PermutedTriangle& F, const std::vector<int>& of,
                    const std::vector<int>& parent) {
  const int count = static_cast<int>(parent.size());
  const int n = static_cast<int>(of.size());
  std::vector<int> mark(n, -1);
  // Children grouped by parent: each parent's rows are marked once for all of them.
  std::vector<int> start(count + 1, 0), children(count);
  for (const int p : parent)
    if (p >= 0) ++start[p + 1];
  for (int t = 0; t < count; ++t) start[t + 1] += start[t];
  std::vector<int> next(start.begin(), start.end() - 1);
  for (int t = 0; t < count; ++t)
    if (parent[t] >= 0) children[next[parent[t]]++] = t;
  for (int t = 0; t < count; ++t) {
    for (int q = k.pi[t]; q < k.pi[t + 1]; ++q) mark[k.s[q]] = t;
    for (int j = k.super[t]; j < k.super[t + 1]; ++j)
      for (int q = F.p[j]; q < F.p[j + 1]; ++q)
        if (mark[F.i[q]] != t) return false;
    for (int c = start[t]; c < start[t + 1]; ++c) {
      const int child = children[c];
      for (int q = k.pi[child] + k.super[child + 1] - k.super[child]; q < k.pi[child + 1]; ++q)
        if (mark[k.s[q]] != t) return false;
    }
  }
  return true;
}

// L->px, the largest update block (maxcsize) and the most rows below a supernode's columns (maxesize), as
// cholmod_super_symbolic2 computes them; false when the values would not fit an int.
bool derivedSizes(const KeptSymbolic& k, const std::vector<int>& of, std::vector<int64_t>& px,
                  int64_t& maxcsize, int64_t& maxesize) {
  const int count = static_cast<int>(k.super.size()) - 1;
  px.assign(count + 1, 0);
  maxcsize = maxesize = 1;
  for (int t = 0; t < count; ++t) {
    const int64_t columns = k.super[t + 1] - k.super[t], rows = k.pi[t + 1] - k.pi[t];
    px[t + 1] = px[t] + columns * rows;
    const int begin = k.pi[t] + static_cast<int>(columns), end = k.pi[t + 1];
    maxesize = std::max<int64_t>(maxesize, end - begin);
    // The rows below split by the ancestor they update; each part's block is its rows by the rows from it on.
    for (int q = begin; q < end;) {
      int r = q;
      while (r < end && of[k.s[r]] == of[k.s[q]]) ++r;
      maxcsize = std::max<int64_t>(maxcsize, static_cast<int64_t>(r - q) * (end - q));
      q = r;
    }
  }
  return px.back() < (int64_t{1} << 31) - 1;
}

}  // namespace

KeptSymbolic keptSymbolicOf(const cholmod_factor& L) {
  KeptSymbolic k;
  if (!L.is_super || L.nsuper == 0) return k;
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  const int* s = static_cast<const int*>(L.s);
  k.super.assign(super, super + L.nsuper + 1);
  k.pi.assign(pi, pi + L.nsuper + 1);
  k.s.assign(s, s + pi[L.nsuper]);
  return k;
}

cholmod_factor* symbolicFromKept(const cholmod_sparse& A, const std::vector<int>& perm,
                                 const KeptSymbolic& kept, int parts, cholmod_common& c,
                                 PermutedTriangle& lower) {
  const int n = static_cast<int>(A.ncol);
  lower = PermutedTriangle();
  if (static_cast<int>(perm.size()) != n || !wellFormed(kept, n)) return nullptr;
  std::vector<int> inverse;
  if (!invert(perm, inverse)) return nullptr;
  lower = permutedTriangle(A, inverse, Triangle::Lower, true, parts);
  std::vector<int> of, parent;
  std::vector<int64_t> px;
  int64_t maxcsize = 0, maxesize = 0;
  supernodeTree(kept, n, of, parent);
  if (!holdsTheFactor(kept, lower, of, parent) || !derivedSizes(kept, of, px, maxcsize, maxesize)) {
    lower = PermutedTriangle();
    return nullptr;
  }
  cholmod_factor* L = cholmod_allocate_factor(n, &c);
  if (!L) {
    lower = PermutedTriangle();
    return nullptr;
  }
  const int count = static_cast<int>(kept.super.size()) - 1;
  std::copy(perm.begin(), perm.end(), static_cast<int*>(L->Perm));
  // Column j of a supernode has the supernode's rows from j on (its pattern is closed: a count that bounds
  // L's, as the conversion to LDL' takes it).
  int* colCount = static_cast<int*>(L->ColCount);
  for (int t = 0; t < count; ++t)
    for (int j = kept.super[t]; j < kept.super[t + 1]; ++j)
      colCount[j] = kept.pi[t + 1] - kept.pi[t] - (j - kept.super[t]);
  L->ordering = CHOLMOD_GIVEN;
  L->ssize = std::max<size_t>(1, kept.s.size());
  L->xsize = std::max<size_t>(1, static_cast<size_t>(px.back()));
  L->nsuper = count;
  // As cholmod_super_symbolic2 makes it: the supernodal pattern allocated, then filled in.
  cholmod_change_factor(CHOLMOD_PATTERN, 1, 1, 1, 1, L, &c);
  if (c.status < CHOLMOD_OK || !L->is_super) {
    cholmod_free_factor(&L, &c);
    lower = PermutedTriangle();
    return nullptr;
  }
  std::copy(kept.super.begin(), kept.super.end(), static_cast<int*>(L->super));
  std::copy(kept.pi.begin(), kept.pi.end(), static_cast<int*>(L->pi));
  std::copy(kept.s.begin(), kept.s.end(), static_cast<int*>(L->s));
  std::transform(px.begin(), px.end(), static_cast<int*>(L->px),
                 [](int64_t v) { return static_cast<int>(v); });
  L->maxcsize = static_cast<size_t>(maxcsize);
  L->maxesize = static_cast<size_t>(maxesize);
  L->useGPU = 0;
  c.lnz = 0;
  for (int j = 0; j < n; ++j) c.lnz += colCount[j];
  return L;
}

}  // namespace tvf
