#pragma once
// RAII ownership of CHOLMOD's workspace and objects (int32 API).
#include <cholmod.h>

#include <memory>

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

}  // namespace tvf
