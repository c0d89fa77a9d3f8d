#pragma once
// RAII ownership of CHOLMOD's workspace and objects (int32 API), and views of the project's matrices.
#include <cholmod.h>

#include <memory>

#include "common/sparse_matrix.h"

namespace tvf {

class CholmodCommon {
 public:
  CholmodCommon() { cholmod_start(&common_); }
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

// A view of a compressed upper triangle as CHOLMOD's packed, sorted, symmetric-upper sparse matrix: nothing
// is copied, so it is valid while `upper` is.
inline cholmod_sparse upperTriangleView(const SparseMatrix& upper) {
  cholmod_sparse s{};
  s.nrow = static_cast<size_t>(upper.rows());
  s.ncol = static_cast<size_t>(upper.cols());
  s.nzmax = static_cast<size_t>(upper.nonZeros());
  s.p = const_cast<int*>(upper.outerIndexPtr());
  s.i = const_cast<int*>(upper.innerIndexPtr());
  s.x = const_cast<double*>(upper.valuePtr());
  s.stype = 1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

}  // namespace tvf
