#pragma once
// Solves with a supernodal LL' factor for a block of right-hand sides, on the lane kernels
// (solver/lane_kernels.h): what the stripe pattern's LOBPCG asks of its factor at every step (four columns).
// In wasm CHOLMOD's supernodal solve calls Eigen's BLAS, one double at a time there. The block is kept by
// rows (a row of the block, all its right-hand sides, side by side), so that each supernode's update is one
// product with its rows below, and its own triangle is solved with the right-hand sides in the vector lanes.
#include <cholmod.h>

namespace tvf {

// x = A^-1 b for L L' = P A P' (L: CHOLMOD's numeric supernodal LL' factor). b and x: n x nrhs, column-major,
// leading dimension n; they may not overlap.
void solveSupernodal(const cholmod_factor& L, const double* b, int nrhs, double* x);

}  // namespace tvf
