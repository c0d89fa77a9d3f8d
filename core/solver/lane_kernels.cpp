#include "solver/lane_kernels.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "common/simd_lanes.h"

namespace tvf::lanes {
namespace {

// Columns of the triangular solve solved together after one product with the columns before them, and of
// the Cholesky factorization's diagonal blocks: the products carry the rest.
constexpr int kSolveBlock = 16;
constexpr int kFactorBlock = 32;

inline Lanes2 splat(double x) {
  return Lanes2{x, x};
}

// acc[r][q] = the sum over p < k of A(rows 2r, 2r + 1; p) B(q; p), A's rows from a, B's from b.
template <int R, int C>
inline void product(int k, const double* a, size_t lda, const double* b, size_t ldb, Lanes2 (&acc)[R][C]) {
  for (int r = 0; r < R; ++r)
    for (int q = 0; q < C; ++q) acc[r][q] = splat(0);
  for (int p = 0; p < k; ++p, a += lda, b += ldb) {
    Lanes2 av[R];
    for (int r = 0; r < R; ++r) av[r] = load2(a + 2 * r);
    for (int q = 0; q < C; ++q) {
      const Lanes2 bq = splat(b[q]);
      for (int r = 0; r < R; ++r) acc[r][q] += av[r] * bq;
    }
  }
}

inline void put(double* p, double v, bool subtract) {
  *p = subtract ? *p - v : v;
}

// acc into C's block at (row, col); with `lower`, only the entries on or below C's diagonal.
template <int R, int C>
inline void store(const Lanes2 (&acc)[R][C], double* c, size_t ldc, int row, int col, bool lower,
                  bool subtract) {
  for (int q = 0; q < C; ++q) {
    for (int r = 0; r < R; ++r) {
      double* p = c + q * ldc + 2 * r;
      const int top = row + 2 * r;
      if (!lower || top >= col + q) {
        store2(p, subtract ? load2(p) - acc[r][q] : acc[r][q]);
      } else if (top + 1 >= col + q) {
        put(p + 1, acc[r][q][1], subtract);
      }
    }
  }
}

// Columns [j, j + C) of C (m rows) from A's rows and B's rows j..j + C - 1; with `lower`, from row j down.
template <int C>
void columns(int j, int m, int k, const double* a, size_t lda, const double* b, size_t ldb, double* c,
             size_t ldc, bool lower, bool subtract) {
  const double* bj = b + j;
  double* cj = c + j * ldc;
  int i = lower ? j : 0;
  for (; i + 4 <= m; i += 4) {
    Lanes2 acc[2][C];
    product<2, C>(k, a + i, lda, bj, ldb, acc);
    store<2, C>(acc, cj + i, ldc, i, j, lower && i < j + C, subtract);
  }
  for (; i + 2 <= m; i += 2) {
    Lanes2 acc[1][C];
    product<1, C>(k, a + i, lda, bj, ldb, acc);
    store<1, C>(acc, cj + i, ldc, i, j, lower && i < j + C, subtract);
  }
  if (i == m) return;
  for (int q = 0; q < C; ++q) {  // the last row, one double at a time
    if (lower && i < j + q) continue;
    double s = 0;
    for (int p = 0; p < k; ++p) s += a[i + p * lda] * bj[q + p * ldb];
    put(cj + i + q * ldc, s, subtract);
  }
}

void blockedProduct(int m, int n, int k, const double* a, int lda, const double* b, int ldb, double* c,
                    int ldc, bool lower, bool subtract) {
  if (m <= 0 || n <= 0) return;
  if (k <= 0) {
    if (subtract) return;
    for (int j = 0; j < n; ++j)
      for (int i = lower ? j : 0; i < m; ++i) c[i + static_cast<size_t>(j) * ldc] = 0;
    return;
  }
  int j = 0;
  for (; j + 4 <= n; j += 4) columns<4>(j, m, k, a, lda, b, ldb, c, ldc, lower, subtract);
  for (; j < n; ++j) columns<1>(j, m, k, a, lda, b, ldb, c, ldc, lower, subtract);
}

// y[0, n) += s x[0, n)
void axpy(int n, double s, const double* x, double* y) {
  const Lanes2 sv = splat(s);
  int i = 0;
  for (; i + 2 <= n; i += 2) store2(y + i, load2(y + i) + sv * load2(x + i));
  if (i < n) y[i] += s * x[i];
}

void scale(int n, double s, double* y) {
  const Lanes2 sv = splat(s);
  int i = 0;
  for (; i + 2 <= n; i += 2) store2(y + i, load2(y + i) * sv);
  if (i < n) y[i] *= s;
}

// The w x w block at d (leading dimension ld), its products with the columns before it already subtracted:
// factored column by column; 0 or the 1-based column whose pivot is not positive.
int factorDiagonalBlock(int w, double* d, size_t ld) {
  for (int j = 0; j < w; ++j) {
    double* column = d + j * ld;
    for (int q = 0; q < j; ++q) axpy(w - j, -d[j + q * ld], d + q * ld + j, column + j);
    const double pivot = column[j];
    if (!(pivot > 0)) return j + 1;
    const double root = std::sqrt(pivot);
    column[j] = root;
    scale(w - j - 1, 1.0 / root, column + j + 1);
  }
  return 0;
}

// c[r][q] = the dot products of columns r of A and q of B (k long), R x C of them at once.
template <int R, int C>
void dots(int k, const double* a, size_t lda, const double* b, size_t ldb, double (&c)[R][C]) {
  Lanes2 acc[R][C];
  for (int r = 0; r < R; ++r)
    for (int q = 0; q < C; ++q) acc[r][q] = splat(0);
  int p = 0;
  for (; p + 2 <= k; p += 2) {
    Lanes2 bv[C];
    for (int q = 0; q < C; ++q) bv[q] = load2(b + q * ldb + p);
    for (int r = 0; r < R; ++r) {
      const Lanes2 av = load2(a + r * lda + p);
      for (int q = 0; q < C; ++q) acc[r][q] += av * bv[q];
    }
  }
  for (int r = 0; r < R; ++r)
    for (int q = 0; q < C; ++q) {
      c[r][q] = acc[r][q][0] + acc[r][q][1];
      if (p < k) c[r][q] += a[r * lda + p] * b[q * ldb + p];
    }
}

}  // namespace

void gemmTN(int m, int n, int k, const double* a, int lda, const double* b, int ldb, double* c, int ldc) {
  const size_t la = static_cast<size_t>(lda), lb = static_cast<size_t>(ldb), lc = static_cast<size_t>(ldc);
  for (int j = 0; j < n; j += 4) {
    const int cols = std::min(4, n - j);
    for (int i = 0; i < m; i += 2) {
      double block[2][4];
      const double* ai = a + i * la;
      const double* bj = b + j * lb;
      if (i + 2 <= m && cols == 4) {
        dots<2, 4>(k, ai, la, bj, lb, block);
      } else {  // an edge: one column pair at a time
        for (int r = 0; r < std::min(2, m - i); ++r)
          for (int q = 0; q < cols; ++q) {
            double one[1][1];
            dots<1, 1>(k, ai + r * la, la, bj + q * lb, lb, one);
            block[r][q] = one[0][0];
          }
      }
      for (int r = 0; r < std::min(2, m - i); ++r)
        for (int q = 0; q < cols; ++q) c[i + r + (j + q) * lc] = block[r][q];
    }
  }
}

void gemmNT(int m, int n, int k, const double* a, int lda, const double* b, int ldb, double* c, int ldc,
            bool subtract) {
  blockedProduct(m, n, k, a, lda, b, ldb, c, ldc, false, subtract);
}

void syrkLower(int n, int k, const double* a, int lda, double* c, int ldc, bool subtract) {
  blockedProduct(n, n, k, a, lda, a, lda, c, ldc, true, subtract);
}

void trsmRightLowerTransposed(int m, int n, const double* l, int ldl, double* b, int ldb) {
  if (m <= 0 || n <= 0) return;
  const size_t ld = static_cast<size_t>(ldb), ldL = static_cast<size_t>(ldl);
  for (int j0 = 0; j0 < n; j0 += kSolveBlock) {
    const int j1 = std::min(n, j0 + kSolveBlock);
    if (j0 > 0) gemmNT(m, j1 - j0, j0, b, ldb, l + j0, ldl, b + j0 * ld, ldb, true);
    for (int j = j0; j < j1; ++j) {
      double* column = b + j * ld;
      for (int q = j0; q < j; ++q) axpy(m, -l[j + q * ldL], b + q * ld, column);
      scale(m, 1.0 / l[j + j * ldL], column);
    }
  }
}

int potrfLower(int n, double* a, int lda) {
  const size_t ld = static_cast<size_t>(lda);
  for (int k0 = 0; k0 < n; k0 += kFactorBlock) {
    const int k1 = std::min(n, k0 + kFactorBlock), w = k1 - k0;
    double* d = a + k0 + k0 * ld;
    if (k0 > 0) {
      syrkLower(w, k0, a + k0, lda, d, lda, true);
      gemmNT(n - k1, w, k0, a + k1, lda, a + k0, lda, d + w, lda, true);
    }
    const int info = factorDiagonalBlock(w, d, ld);
    if (info != 0) return k0 + info;
    trsmRightLowerTransposed(n - k1, w, d, lda, d + w, lda);
  }
  return 0;
}

}  // namespace tvf::lanes
