#pragma once
// RAII ownership of CHOLMOD's workspace and objects (int32 API), and views of the project's matrices.
#include <cholmod.h>

#include <memory>

#include "common/sparse_matrix.h"

namespace tvf {

class CholmodCommon {
 public:
  // CHOLMOD probes METIS's memory with a trial allocation of 2 x (10 nnz + 50 n) words first (metis_memory);
  // in wasm that grows the heap for good (~140 MB on bunny00, ~1.5 GB at 1.25M edges), and METIS 5 reports
  // running out of memory itself (CHOLMOD then falls back to AMD). Every common the project makes skips it.
  CholmodCommon() {
    cholmod_start(&common_);
    common_.metis_memory = 0;
  }
  ~CholmodCommon() { cholmod_finish(&common_); }
  CholmodCommon(const CholmodCommon&) = delete;
  CholmodCommon& operator=(const CholmodCommon&) = delete;
  cholmod_common* get() { return &common_; }
  cholmod_common* operator->() { return &common_; }

 private:
  cholmod_common common_;
};

// Deleters need the common object that allocated the memory; it must outlive every handle made with it.
struct CholmodFactorDeleter {
  cholmod_common* common;
  void operator()(cholmod_factor* p) const { cholmod_free_factor(&p, common); }
};
struct CholmodSparseDeleter {
  cholmod_common* common;
  void operator()(cholmod_sparse* p) const { cholmod_free_sparse(&p, common); }
};
struct CholmodDenseDeleter {
  cholmod_common* common;
  void operator()(cholmod_dense* p) const { cholmod_free_dense(&p, common); }
};

using CholmodFactorPtr = std::unique_ptr<cholmod_factor, CholmodFactorDeleter>;
using CholmodSparsePtr = std::unique_ptr<cholmod_sparse, CholmodSparseDeleter>;
using CholmodDensePtr = std::unique_ptr<cholmod_dense, CholmodDenseDeleter>;

// A view of compressed columns as CHOLMOD's packed sparse matrix (stype +1: the upper triangle of a symmetric
// one, -1: its lower; x null: the pattern alone): nothing is copied, so it is valid while the arrays are.
inline cholmod_sparse compressedView(size_t n, size_t nnz, const int* p, const int* i, const double* x,
                                     int stype, bool sorted) {
  cholmod_sparse s{};
  s.nrow = s.ncol = n;
  s.nzmax = nnz;
  s.p = const_cast<int*>(p);
  s.i = const_cast<int*>(i);
  s.x = const_cast<double*>(x);
  s.stype = stype;
  s.itype = CHOLMOD_INT;
  s.xtype = x ? CHOLMOD_REAL : CHOLMOD_PATTERN;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = sorted;
  s.packed = 1;
  return s;
}

// A compressed upper triangle as CHOLMOD's sorted, symmetric-upper sparse matrix.
inline cholmod_sparse upperTriangleView(const SparseMatrix& upper) {
  return compressedView(static_cast<size_t>(upper.cols()), static_cast<size_t>(upper.nonZeros()),
                        upper.outerIndexPtr(), upper.innerIndexPtr(), upper.valuePtr(), 1, true);
}

}  // namespace tvf
