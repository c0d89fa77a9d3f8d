/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The complex BLAS/LAPACK routines that CHOLMOD's supernodal code references (its complex and zomplex
 * factorizations share an object file with the real one), for the wasm archive of wasm/build-cholmod.sh.
 * The project factors real matrices only (CHOLMOD_REAL, never CHOLMOD_COMPLEX or CHOLMOD_ZOMPLEX), so none of
 * these is ever called: each one stops the program rather than return a wrong factor. Eigen's complex BLAS
 * (blas/complex_double.cpp, the archive's slowest file to compile) and complex Cholesky were about 650 KB of
 * its objects, for code no field reaches. The prototypes are the patched cholmod_blas.h's (int results), so
 * the compiler checks these against them.
 */
#include <stdio.h>
#include <stdlib.h>

#include "cholmod_blas.h"

static int never(const char* name) {
  fprintf(stderr, "CHOLMOD called the complex %s: this build factors real matrices only\n", name);
  abort();
}

int BLAS_ZGEMV(char* trans, BLAS_INT* m, BLAS_INT* n, double* alpha, double* A, BLAS_INT* lda, double* X,
               BLAS_INT* incx, double* beta, double* Y, BLAS_INT* incy) {
  return never("zgemv");
}

int BLAS_ZTRSV(char* uplo, char* trans, char* diag, BLAS_INT* n, double* A, BLAS_INT* lda, double* X,
               BLAS_INT* incx) {
  return never("ztrsv");
}

int BLAS_ZTRSM(char* side, char* uplo, char* transa, char* diag, BLAS_INT* m, BLAS_INT* n, double* alpha,
               double* A, BLAS_INT* lda, double* B, BLAS_INT* ldb) {
  return never("ztrsm");
}

int BLAS_ZGEMM(char* transa, char* transb, BLAS_INT* m, BLAS_INT* n, BLAS_INT* k, double* alpha, double* A,
               BLAS_INT* lda, double* B, BLAS_INT* ldb, double* beta, double* C, BLAS_INT* ldc) {
  return never("zgemm");
}

int BLAS_ZHERK(char* uplo, char* trans, BLAS_INT* n, BLAS_INT* k, double* alpha, double* A, BLAS_INT* lda,
               double* beta, double* C, BLAS_INT* ldc) {
  return never("zherk");
}

int LAPACK_ZPOTRF(char* uplo, BLAS_INT* n, double* A, BLAS_INT* lda, BLAS_INT* info) {
  return never("zpotrf");
}
