#pragma once
// Procedurally generated, seamlessly tiling exemplars shared by the page (through wasm) and the native tests, so
// that both synthesize from exactly the same pixels without shipping image files:
//   "stripes": wavy two-tone bands along the x-axis (period size/4), with fibre-like grain — the orientation test
//              pattern (its stripes run along the exemplar's x-axis);
//   "scales":  overlapping fish scales in offset rows (cell size/4 wide, size/8 high), shaded with a dark rim;
//   "weave":   basket weave, 4x4 blocks of alternating horizontal/vertical threads.
// Deterministic for a given (name, size, seed); every pattern's period divides `size` (a power of two >= 16).
#include <string>
#include <vector>

#include "texture/exemplar_image.h"

namespace tvf {

std::vector<std::string> proceduralExemplarNames();
// Throws InputError for an unknown name or a size that is not a power of two in [16, 1024].
ExemplarImage makeProceduralExemplar(const std::string& name, int size, unsigned seed = 1);

// Seamless value noise with cellsX x cellsY lattice cells across the torus of side `size`, values in [0, 1].
float tileableNoise(float x, float y, int size, int cellsX, int cellsY, unsigned seed);

}  // namespace tvf
