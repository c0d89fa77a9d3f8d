#pragma once
// The BLAS and LAPACK routines CHOLMOD's supernodal factorization calls, declared for the project's own
// supernodal kernels (solver/supernodal_cholesky.h), which call the same ones so that both factor alike.
// Fortran calling convention: every argument by pointer, no hidden string lengths (as cholmod_blas.h).
// The wasm build's BLAS is Eigen's, whose routines return int (wasm/build-cholmod.sh); a native BLAS's
// return nothing.
//
// Small blocks, most of a mesh's supernodes, go to Eigen's kernels inline instead: a native BLAS may take a
// lock of its own for each call's buffers (OpenBLAS's blas_memory_alloc), which threads factoring side by
// side then wait on (bunny00 natively: each of two subtrees 45 ms alone, 95 ms together).
//
// In wasm every block goes to the two-lane kernels (solver/lane_kernels.h): Eigen 3.4 has no wasm SIMD, so
// both its inline products and its BLAS run there one double at a time.
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "solver/lane_kernels.h"

namespace tvf::blas {

#ifdef __EMSCRIPTEN__
constexpr bool kLaneKernels = true;
#else
constexpr bool kLaneKernels = false;
#endif

#ifdef __EMSCRIPTEN__
using Status = int;
#else
using Status = void;
#endif

extern "C" {
Status dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha,
              const double* a, const int* lda, const double* beta, double* c, const int* ldc);
Status dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
              const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
              const double* beta, double* c, const int* ldc);
Status dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m,
              const int* n, const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
Status dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
}

// While it lives, a native OpenBLAS runs each call on the calling thread alone: the factorization's own
// threads each call it, and OpenBLAS's own pool working beside them made two threads on bunny00 take
// 217 ms where one took 144. Found at run time (the BLAS may be another); nothing in wasm.
class BlasOnCallingThread {
 public:
  BlasOnCallingThread();
  ~BlasOnCallingThread();
  BlasOnCallingThread(const BlasOnCallingThread&) = delete;
  BlasOnCallingThread& operator=(const BlasOnCallingThread&) = delete;

 private:
  int restore_ = 0;
};

// Multiply-adds up to which a call stays inline.
constexpr double kInlineFlops = 48.0 * 48.0 * 48.0;

using Block = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using ConstBlock = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;

// C (n x n, lower) = A A' for A n x k; column-major, leading dimensions as given.
inline void syrkLower(int n, int k, const double* a, int lda, double* c, int ldc) {
  if constexpr (kLaneKernels) return lanes::syrkLower(n, k, a, lda, c, ldc, false);
  if (0.5 * n * n * k > kInlineFlops) {
    const double one = 1, zero = 0;
    dsyrk_("L", "N", &n, &k, &one, a, &lda, &zero, c, &ldc);
    return;
  }
  ConstBlock A(a, n, k, Eigen::OuterStride<>(lda));
  Block C(c, n, n, Eigen::OuterStride<>(ldc));
  C.triangularView<Eigen::Lower>().setZero();
  C.selfadjointView<Eigen::Lower>().rankUpdate(A);
}

// C (m x n) = A B' for A m x k, B n x k.
inline void gemmNT(int m, int n, int k, const double* a, int lda, const double* b, int ldb, double* c,
                   int ldc) {
  if constexpr (kLaneKernels) return lanes::gemmNT(m, n, k, a, lda, b, ldb, c, ldc, false);
  if (static_cast<double>(m) * n * k > kInlineFlops) {
    const double one = 1, zero = 0;
    dgemm_("N", "T", &m, &n, &k, &one, a, &lda, b, &ldb, &zero, c, &ldc);
    return;
  }
  ConstBlock A(a, m, k, Eigen::OuterStride<>(lda));
  ConstBlock B(b, n, k, Eigen::OuterStride<>(ldb));
  Block C(c, m, n, Eigen::OuterStride<>(ldc));
  C.noalias() = A.lazyProduct(B.transpose());
}

// C (m x n) -= A B' for A m x k, B n x k.
inline void gemmNTSubtract(int m, int n, int k, const double* a, int lda, const double* b, int ldb, double* c,
                           int ldc) {
  if (m <= 0 || n <= 0 || k <= 0) return;
  if constexpr (kLaneKernels) return lanes::gemmNT(m, n, k, a, lda, b, ldb, c, ldc, true);
  if (static_cast<double>(m) * n * k > kInlineFlops) {
    const double minusOne = -1, one = 1;
    dgemm_("N", "T", &m, &n, &k, &minusOne, a, &lda, b, &ldb, &one, c, &ldc);
    return;
  }
  ConstBlock A(a, m, k, Eigen::OuterStride<>(lda));
  ConstBlock B(b, n, k, Eigen::OuterStride<>(ldb));
  Block C(c, m, n, Eigen::OuterStride<>(ldc));
  C.noalias() -= A.lazyProduct(B.transpose());
}

// C (n x n, lower) -= A A' for A n x k.
inline void syrkLowerSubtract(int n, int k, const double* a, int lda, double* c, int ldc) {
  if (n <= 0 || k <= 0) return;
  if constexpr (kLaneKernels) return lanes::syrkLower(n, k, a, lda, c, ldc, true);
  if (0.5 * n * n * k > kInlineFlops) {
    const double minusOne = -1, one = 1;
    dsyrk_("L", "N", &n, &k, &minusOne, a, &lda, &one, c, &ldc);
    return;
  }
  ConstBlock A(a, n, k, Eigen::OuterStride<>(lda));
  Block C(c, n, n, Eigen::OuterStride<>(ldc));
  C.selfadjointView<Eigen::Lower>().rankUpdate(A, -1.0);
}

// B (m x n) = B L'^-1 for L n x n lower triangular.
inline void trsmRightLowerTransposed(int m, int n, const double* l, int ldl, double* b, int ldb) {
  if (m <= 0 || n <= 0) return;
  if constexpr (kLaneKernels) return lanes::trsmRightLowerTransposed(m, n, l, ldl, b, ldb);
  if (0.5 * m * n * n > kInlineFlops) {
    const double one = 1;
    dtrsm_("R", "L", "T", "N", &m, &n, &one, l, &ldl, b, &ldb);
    return;
  }
  ConstBlock L(l, n, n, Eigen::OuterStride<>(ldl));
  Block B(b, m, n, Eigen::OuterStride<>(ldb));
  L.transpose().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(B);
}

// The lower Cholesky factor of the n x n block at a, in place; 0, or the 1-based column that is not
// positive.
inline int potrfLower(int n, double* a, int lda) {
  if constexpr (kLaneKernels) return lanes::potrfLower(n, a, lda);
  int info = 0;
  if (n * n * (n / 3.0) > kInlineFlops) {
    dpotrf_("L", &n, a, &lda, &info);
    return info;
  }
  Block A(a, n, n, Eigen::OuterStride<>(lda));
  const Eigen::Index bad = Eigen::internal::llt_inplace<double, Eigen::Lower>::blocked(A);
  return bad < 0 ? 0 : static_cast<int>(bad) + 1;
}

}  // namespace tvf::blas
