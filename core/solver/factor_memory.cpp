#include "solver/factor_memory.h"

#include <SuiteSparse_config.h>
#include <malloc.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <utility>

namespace tvf::factor_memory {
namespace {

struct Held {
  void* block = nullptr;
  size_t bytes = 0;
};

// CHOLMOD allocates on whichever thread calls it.
struct Keeper {
  std::mutex mutex;
  bool keeping = false;
  Held held[kHeldBlocks];  // the largest let go, largest first
};

Keeper& keeper() {
  static Keeper k;
  return k;
}

// The block held, when it suits a request of n bytes.
void* take(size_t n) {
  if (n < kBigBytes) return nullptr;
  Keeper& k = keeper();
  const std::lock_guard<std::mutex> lock(k.mutex);
  for (Held& h : k.held)
    if (h.block && h.bytes >= n && h.bytes - n <= h.bytes / 4) return std::exchange(h, Held()).block;
  return nullptr;
}

void* keptMalloc(size_t n) {
  if (void* p = take(n)) return p;
  return std::malloc(n);
}

void* keptCalloc(size_t count, size_t size) {
  if (size != 0 && count > static_cast<size_t>(-1) / size) return nullptr;
  if (void* p = take(count * size)) return std::memset(p, 0, count * size);
  return std::calloc(count, size);
}

// A big block shrunk keeps its room (the conversion to LDL' shrinks the supernodal values in place), so that
// the next factorization of the same mesh finds the block it had.
void* keptRealloc(void* p, size_t n) {
  if (p && n >= kBigBytes && n <= malloc_usable_size(p)) return p;
  return std::realloc(p, n);
}

void keptFree(void* p) {
  if (!p) return;
  Keeper& k = keeper();
  {
    const std::lock_guard<std::mutex> lock(k.mutex);
    const size_t bytes = malloc_usable_size(p);
    if (k.keeping && bytes >= kBigBytes) {
      // In at its rank; what falls off the end is freed.
      Held in{p, bytes};
      for (Held& h : k.held)
        if (in.bytes > h.bytes) std::swap(in, h);
      p = in.block;
    }
  }
  std::free(p);
}

}  // namespace

void install(bool natively) {
#ifndef __EMSCRIPTEN__
  if (!natively) return;
#endif
  static std::once_flag once;
  std::call_once(once, [] {
    SuiteSparse_config.malloc_func = keptMalloc;
    SuiteSparse_config.calloc_func = keptCalloc;
    SuiteSparse_config.realloc_func = keptRealloc;
    SuiteSparse_config.free_func = keptFree;
  });
}

void keepWhatIsFreed() {
  Keeper& k = keeper();
  const std::lock_guard<std::mutex> lock(k.mutex);
  k.keeping = true;
}

void releaseKept() {
  Keeper& k = keeper();
  Held held[kHeldBlocks];
  {
    const std::lock_guard<std::mutex> lock(k.mutex);
    k.keeping = false;
    for (int b = 0; b < kHeldBlocks; ++b) held[b] = std::exchange(k.held[b], Held());
  }
  for (const Held& h : held) std::free(h.block);
}

size_t keptBytes() {
  Keeper& k = keeper();
  const std::lock_guard<std::mutex> lock(k.mutex);
  size_t bytes = 0;
  for (const Held& h : k.held) bytes += h.bytes;
  return bytes;
}

}  // namespace tvf::factor_memory
