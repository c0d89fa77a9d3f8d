#pragma once
// Where the next factor's values go, in wasm. The heap there never shrinks, and memory the process has not
// touched yet costs a page fault a page when first written, which Chromium's renderer pays slowly: writing
// 800 MB of fresh heap took 280-740 ms there, 270 ms under node (docs/benchmarks.md). A model opened again
// over itself lets its old factor go just before the new one is made (Designer::releaseFactors), but the
// new model, built meanwhile, splits the room the old factor leaves, and the new factor's values land on
// fresh heap above it: 0.65-0.95 s more for armadillo-sub2's 773 MB (96.7M doubles). So CHOLMOD's
// allocations go through a keeper that holds the largest blocks of the factor let go aside, whole, for the
// next factorization's values and row indices of about their size, and frees them when that factorization
// ends. Natively (memory returned to the system, nothing to gain) CHOLMOD allocates as it always does.
#include <cstddef>

namespace tvf::factor_memory {

// Blocks below this are allocated and freed as always.
constexpr size_t kBigBytes = size_t{64} << 20;
// The factor's values and, after its conversion to LDL', its row indices: the two blocks held.
constexpr int kHeldBlocks = 2;

// CHOLMOD's allocations through the keeper, once per process: in wasm; natively only when asked (tests).
void install(bool natively = false);

// The kHeldBlocks largest CHOLMOD blocks of at least kBigBytes freed from now until releaseKept() are held,
// not freed; a request of the size of one, or up to a quarter less, is given it. For a model about to be
// replaced by the same mesh (wasm/bindings.cpp commitModel): another model's factor, of other sizes, would
// only find the held blocks in its way.
void keepWhatIsFreed();

// Frees the block held, if any, and ends keepWhatIsFreed().
void releaseKept();

// The bytes held now (for tests).
size_t keptBytes();

}  // namespace tvf::factor_memory
