#include "solver/ldl_conversion.h"

#include <algorithm>
#include <cstdint>
#include <new>
#include <vector>

#include "common/thread_team.h"
#include "solver/supernodes.h"

namespace tvf {
namespace {

// Entries of supernode s in the packed simplicial factor: its diagonal block's lower triangle and the rows
// below it.
int64_t packedEntries(const Supernodes& sn, int s) {
  const int64_t nscol = sn.cols(s), nsrow = sn.rows(s);
  return nscol * (nscol + 1) / 2 + nscol * (nsrow - nscol);
}

// Supernode s's columns in the packed form from `block` (its supernodal values, in place or a copy) to
// x + start: their starts, lengths and row indices, d = l_jj^2 on the diagonal (l_jj itself where it is not
// positive, as CHOLMOD leaves it) and l_ij / l_jj below. In place each value lands at or before where it
// was read, after every read before it: the order CHOLMOD moves them in.
void convertSupernode(const Supernodes& sn, int s, const double* block, int64_t start, int* Lp, int* Lnz,
                      int* Li) {
  const int nscol = sn.cols(s), nsrow = sn.rows(s), k1 = sn.first(s);
  const int* rows = sn.rowsOf(s);
  double* x = sn.x;
  int64_t p = start;
  for (int jj = 0; jj < nscol; ++jj) {
    const int j = k1 + jj;
    const double* column = block + static_cast<size_t>(jj) * nsrow;
    Lp[j] = static_cast<int>(p);
    Lnz[j] = nsrow - jj;
    double ljj = column[jj];
    if (ljj <= 0)
      x[p] = ljj, ljj = 1;
    else
      x[p] = ljj * ljj;
    Li[p++] = j;
    for (int ii = jj + 1; ii < nsrow; ++ii, ++p) {
      Li[p] = rows[ii];
      x[p] = column[ii] / ljj;
    }
  }
}

// Columns in natural order in the factor's doubly linked list (head n + 1, tail n), as CHOLMOD keeps it.
void naturalList(int n, int* next, int* prev) {
  const int head = n + 1, tail = n;
  next[head] = 0;
  prev[head] = -1;
  next[tail] = -1;
  prev[tail] = n - 1;
  for (int j = 0; j < n; ++j) {
    next[j] = j + 1;
    prev[j] = j - 1;
  }
  prev[0] = head;
}

// The supernodes cut into `parts` runs of about equal entries, bounds[k] .. bounds[k+1], and where each
// run's values must be read from a copy: part k writes from start[bounds[k]] on, over the tail of part
// k - 1's values, which that part then reads from copied[k - 1] (from supernode fromCopy[k - 1] on). False
// where a part would write over values two parts back (a compaction larger than a part: not on a mesh's
// factor), for fewer parts.
struct Plan {
  std::vector<int> bounds, fromCopy;
  std::vector<std::vector<double>> copied;
};

bool plan(const Supernodes& sn, const std::vector<int64_t>& start, int parts, Plan& out) {
  std::vector<int>& bounds = out.bounds;
  bounds.assign(parts + 1, sn.count);
  bounds[0] = 0;
  const int64_t total = start[sn.count];
  for (int s = 0, k = 1; s < sn.count && k < parts; ++s)
    while (k < parts && start[s + 1] * parts >= total * k) bounds[k++] = s + 1;
  out.fromCopy.assign(parts, sn.count);
  for (int k = 1; k < parts; ++k) {
    const int64_t writesFrom = start[bounds[k]];
    if (sn.px[bounds[k - 1]] > writesFrom) return false;
    int t = bounds[k - 1];
    while (t < bounds[k] && sn.px[t + 1] <= writesFrom) ++t;
    out.fromCopy[k - 1] = t;
  }
  return true;
}

}  // namespace

bool convertToSimplicialLdl(cholmod_factor& L, cholmod_common& c, int parts) {
  if (parts <= 1 || !L.is_super || !L.is_ll || L.xtype != CHOLMOD_REAL || L.i != nullptr || L.nsuper < 2)
    return cholmod_change_factor(CHOLMOD_REAL, 0, 0, 1, 1, &L, &c) != 0;
  const Supernodes sn = supernodesOf(L);
  std::vector<int64_t> start(sn.count + 1, 0);
  for (int s = 0; s < sn.count; ++s) start[s + 1] = start[s] + packedEntries(sn, s);
  Plan p;
  parts = std::min(parts, sn.count);
  while (parts > 1 && !plan(sn, start, parts, p)) --parts;
  // The copies first: where there is no room for them, CHOLMOD converts on one thread.
  try {
    p.copied.resize(parts - 1);
    for (int k = 0; k + 1 < parts; ++k)
      p.copied[k].assign(sn.x + sn.px[p.fromCopy[k]], sn.x + sn.px[p.bounds[k + 1]]);
  } catch (const std::bad_alloc&) {
    parts = 1;
  }
  if (parts <= 1) return cholmod_change_factor(CHOLMOD_REAL, 0, 0, 1, 1, &L, &c) != 0;
  c.status = CHOLMOD_OK;
  const size_t n = L.n, lnz = static_cast<size_t>(start[sn.count]);
  auto* Li = static_cast<int*>(cholmod_malloc(lnz, sizeof(int), &c));
  auto* Lp = static_cast<int*>(cholmod_malloc(n + 1, sizeof(int), &c));
  auto* Lnz = static_cast<int*>(cholmod_malloc(n, sizeof(int), &c));
  auto* prev = static_cast<int*>(cholmod_malloc(n + 2, sizeof(int), &c));
  auto* next = static_cast<int*>(cholmod_malloc(n + 2, sizeof(int), &c));
  if (c.status < CHOLMOD_OK) {
    cholmod_free(n + 2, sizeof(int), next, &c);
    cholmod_free(n + 2, sizeof(int), prev, &c);
    cholmod_free(n, sizeof(int), Lnz, &c);
    cholmod_free(n + 1, sizeof(int), Lp, &c);
    cholmod_free(lnz, sizeof(int), Li, &c);
    return false;
  }
  naturalList(static_cast<int>(n), next, prev);
  ThreadTeam::shared().run(parts, [&](int k) {
    for (int s = p.bounds[k]; s < p.bounds[k + 1]; ++s) {
      const bool copied = k + 1 < parts && s >= p.fromCopy[k];
      const double* block = copied ? p.copied[k].data() + (sn.px[s] - sn.px[p.fromCopy[k]]) : sn.block(s);
      convertSupernode(sn, s, block, start[s], Lp, Lnz, Li);
    }
  });
  Lp[n] = static_cast<int>(lnz);
  L.is_ll = 0;
  L.p = Lp;
  L.nz = Lnz;
  L.prev = prev;
  L.next = next;
  L.is_monotonic = 1;
  L.i = Li;
  L.nzmax = lnz;
  // The values shrunk to the packed size, as CHOLMOD does (in wasm the factor's memory keeper decides).
  L.x = cholmod_realloc(lnz, sizeof(double), L.x, &L.xsize, &c);
  const size_t nsuper1 = L.nsuper + 1;
  L.super = cholmod_free(nsuper1, sizeof(int), L.super, &c);
  L.pi = cholmod_free(nsuper1, sizeof(int), L.pi, &c);
  L.px = cholmod_free(nsuper1, sizeof(int), L.px, &c);
  L.s = cholmod_free(L.ssize, sizeof(int), L.s, &c);
  L.ssize = 0;
  L.xsize = 0;
  L.nsuper = 0;
  L.maxesize = 0;
  L.maxcsize = 0;
  L.is_super = 0;
  return true;
}

}  // namespace tvf
