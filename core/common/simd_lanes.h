#pragma once
// Two doubles in one vector register: SSE2 natively, simd128 in wasm (the GCC and Clang vector extension),
// for the solver's kernels whose loops the compilers do not vectorize by themselves.
#include <cstring>

namespace tvf {

typedef double Lanes2 __attribute__((vector_size(16)));

inline Lanes2 load2(const double* p) {
  Lanes2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store2(double* p, Lanes2 v) {
  std::memcpy(p, &v, sizeof v);
}

}  // namespace tvf
