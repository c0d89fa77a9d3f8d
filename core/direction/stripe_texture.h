#pragma once
// A stripe pattern (direction/stripe_pattern.h) drawn into a texture atlas, for a GLB's base colour: per
// texel centre inside a face's UV triangle, the face's phase at the texel's barycentric point (branch faces
// with their piecewise-linear angle), through a profile: stripes 0.5 + 0.5 cos(phase) for one family, grid
// lines (the darker of the two families' stripes, narrowed) for two. Texels outside every triangle take a
// covered neighbour's colour, `gutter` texels out, so bilinear lookups at chart borders read stripes, not
// background. Texel (x, y) has its centre at UV ((x + 0.5) / size, (y + 0.5) / size): row 0 is v = 0, as glTF
// samples.
#include <cstdint>
#include <vector>

#include "direction/stripe_pattern.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct StripeColours {
  uint8_t light[3] = {236, 228, 212};
  uint8_t dark[3] = {52, 44, 40};
};

// RGBA8, 4 per texel, row 0 first; alpha 255 where covered or filled, 0 elsewhere. cornerUVs: 6 per face.
// Throws InputError for a size outside [1, 8192] or cornerUVs of the wrong size.
std::vector<uint8_t> stripeTextureRgba(const SurfaceMesh& mesh, const StripePattern& pattern,
                                       const std::vector<float>& cornerUVs, int size, int gutterTexels,
                                       const StripeColours& colours = {});

// The profile's value in [0, 1] (0 dark, 1 light) at a point of face f with barycentric b.
double stripeValue(const StripePattern& pattern, int32_t numFaces, int32_t f, const double b[3]);

}  // namespace tvf
