#pragma once
// The supernodal factorization's dense kernels (solver/dense_kernels.h) on two-lane vectors: the wasm build's
// own, where Eigen (3.4) has no SIMD and its BLAS runs one double at a time. Register-blocked 4 x 4 products
// with the triangular solve and the Cholesky factorization blocked onto them, so that nearly all their work
// is in the products. Column-major, leading dimensions as given; natively they compile to SSE2 and are tested
// there against plain loops.

namespace tvf::lanes {

// C (m x n) = A B', or C -= A B' (subtract), for A m x k and B n x k.
void gemmNT(int m, int n, int k, const double* a, int lda, const double* b, int ldb, double* c, int ldc,
            bool subtract);

// C (m x n) = A' B for A k x m and B k x n: the Gram products of tall matrices (k long, m and n small).
void gemmTN(int m, int n, int k, const double* a, int lda, const double* b, int ldb, double* c, int ldc);

// C (n x n) = A A', or C -= A A', for A n x k: the lower triangle only, the strict upper left as it was.
void syrkLower(int n, int k, const double* a, int lda, double* c, int ldc, bool subtract);

// B (m x n) = B L'^-1 for L n x n lower triangular.
void trsmRightLowerTransposed(int m, int n, const double* l, int ldl, double* b, int ldb);

// The lower Cholesky factor of the n x n block at a, in place (the strict upper triangle untouched); 0, or
// the 1-based column whose pivot is not positive.
int potrfLower(int n, double* a, int lda);

}  // namespace tvf::lanes
