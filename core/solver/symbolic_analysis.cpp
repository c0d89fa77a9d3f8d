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

}  // namespace tvf
