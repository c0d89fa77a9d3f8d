#pragma once
// A stripe pattern (direction/stripe_pattern.h) drawn into a texture atlas, for a GLB's base colour: per
// texel centre inside a face's UV triangle, the face's phase at the texel's barycentric point (branch faces
// with their piecewise-linear angle), through a profile (StripeProfile), filtered over the texel's footprint.
// The page draws the same profiles per fragment (web/stripes/profiles.js): the same formulas, so that a GLB
// shows what the page showed. The footprint is each vertex's largest over its faces, interpolated, so a line
// is filtered alike either side of a chart seam. Texels within 1.5 texels outside a chart take the pattern
// continued from its nearest face (a bilinear lookup at the chart's edge reads the pattern there), and those
// further out a covered neighbour's colour, `gutter` texels out, so lookups at chart borders read stripes,
// not background. Texel (x, y) has its centre at UV ((x + 0.5) / size, (y + 0.5) / size): row 0 is v = 0, as
// glTF samples.
#include <cstdint>
#include <string>
#include <vector>

#include "direction/stripe_pattern.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// How a phase becomes a colour. x = phase / 2 pi of the first family (periods), y of the second. Every
// profile reads the same where a line field's phase runs the other way (x -> -x + k, k whole): the
// representatives' signs leave no seam. The widths below are the defaults (stripeDefaultWidth); a width asked
// for sets the dark share of a period instead.
//  Stripes: dark bands half a period wide round whole x (their edges where cos(phase) = 0).
//  WoodRings: a ring per period, light early wood darkening towards a late-wood line at whole x.
//  GridLines: lines 0.12 of a period wide at whole x and at whole y.
//  Bricks, Weave: of a pattern at half the frequency (stripePatternFrequencyFactor), whose whole periods keep
//  the parity of a row or a thread across every edge: X = 2x, Y = 2y. Bricks: mortar at half-whole X (a row
//  per period of the asked frequency), head joints every two periods of Y, shifted one on every other row.
//  Weave: threads centred on whole X and on whole Y, over and under in a checkerboard.
enum class StripeProfile { Stripes, WoodRings, GridLines, Bricks, Weave };

// "stripes", "wood", "grid", "bricks", "weave"; throws InputError naming the choices.
StripeProfile stripeProfileNamed(const std::string& name);
const char* stripeProfileName(StripeProfile profile);
// Grid lines, bricks and weave need two families of stripes.
bool stripeProfileHasTwoFamilies(StripeProfile profile);
// The pattern a profile draws is computed at this times the asked frequency (1, or 1/2 for bricks and weave).
double stripePatternFrequencyFactor(StripeProfile profile);

struct StripeColours {
  uint8_t light[3] = {236, 228, 212};
  uint8_t dark[3] = {52, 44, 40};
};

// The width of a profile's lines as a share of a period (in [0, 1]), unless asked otherwise: the dark bands
// of Stripes (1/2), WoodRings' darkening late wood (0.7), GridLines' lines and Bricks' mortar (0.12; the head
// joints half as wide, in the rows' units), and Weave's threads (1: no gap between them).
double stripeDefaultWidth(StripeProfile profile);

// The profile's value in [0, 1] (0 dark, 1 light) at x, y (periods), filtered over a footprint of w periods,
// its lines `width` of a period wide (not > 0: stripeDefaultWidth).
double stripeProfileValue(StripeProfile profile, double x, double y, double w, double width = 0);

// RGBA8, 4 per texel, row 0 first; alpha 255 where covered or filled, 0 elsewhere. cornerUVs: 6 per face.
// Throws InputError for a size outside [1, 8192], cornerUVs of the wrong size, or a profile that needs two
// families drawn from a pattern of one, or a width outside (0, 1] (0: the profile's own).
std::vector<uint8_t> stripeTextureRgba(const SurfaceMesh& mesh, const StripePattern& pattern,
                                       const std::vector<float>& cornerUVs, int size, int gutterTexels,
                                       const StripeColours& colours = {},
                                       StripeProfile profile = StripeProfile::Stripes, double width = 0);

// The phase as a texture coordinate (an engine's own pattern reads it: TEXCOORD_1 of the GLB), 2 per face
// corner: each family's phase at the corner in periods (the second 0 for one family). Each face is shifted by
// whole periods so that the phase continues across every edge where it can; where it cannot (round a branch
// point, across a line field's sign flip or a cross field's family swap) the edge is a seam and its corners
// differ. Inside a branch face the coordinate is the corners' linear interpolation, not the pattern's turn.
std::vector<float> stripeTexcoords(const SurfaceMesh& mesh, const MeshTopology& topology,
                                   const StripePattern& pattern);

// A family's phase (radians) at a point of face f with barycentric b.
double stripePhase(const StripePattern& pattern, int32_t numFaces, int family, int32_t f, const double b[3]);

}  // namespace tvf
