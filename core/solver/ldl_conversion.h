#pragma once
// The supernodal LL' factor turned into the simplicial LDL' form the rank-1 updates need: the arrays
// cholmod_change_factor(CHOLMOD_REAL, 0, 0, 1, 1) makes of it, bit for bit, with the per-entry work (every
// value divided by its column's pivot, every row index written) on several threads. CHOLMOD does it on one,
// after a factorization that runs on all of them: armadillo-sub2 in wasm 302 ms of a 7.5 s factorization on
// one thread, 200 ms with two. The values move down in place; where one part writes over the values of the
// part before, those are read from a copy made first (on armadillo-sub2 with two parts, 6 % of the values).
#include <cholmod.h>

namespace tvf {

// L (supernodal, numeric LL') becomes simplicial, packed, monotonic LDL' with D on the diagonal, as CHOLMOD
// converts it; `parts` threads (common/thread_team.h) share the supernodes. One part, or a factor not
// supernodal LL', is left to cholmod_change_factor. False, with c.status set, where the memory ran out.
bool convertToSimplicialLdl(cholmod_factor& L, cholmod_common& c, int parts);

}  // namespace tvf
