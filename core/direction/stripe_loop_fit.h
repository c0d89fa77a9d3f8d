#pragma once
// Stripes fitted to the surface's loops. On a surface with a handle or a tube, stripes that cross a loop of
// it close up only with a whole number of them along the loop, and the stripes running beside it only where
// the field's lines close up after a whole number of stripes round it: where the asked frequency puts a
// fraction there, the eigenvector turns its stripes off the field to make up the difference, over as much of
// the surface as the loop passes through. Which whole numbers the pattern takes changes every half a percent
// of frequency on knot2 (a tube round a knot, 11.5k faces, a line field with no singularity), and its stripes
// read 0.30, 0.75 and 1.16 degrees off the field on the exported texture at 12.2, 12.7 and 13 stripes per
// unit. A whole pattern on such a surface therefore tries frequencies close to the asked one and keeps the
// one whose stripes follow the field best (StripeOptions::fitLoops).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dec/hodge_star.h"
#include "direction/stripe_lift.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf::stripe {

// The factors of the asked frequency tried: 1, then 1 -+ kFitStep, 1 -+ 2 kFitStep, ... to kFitSteps each
// way.
constexpr int kFitSteps = 5;
constexpr double kFitStep = 0.01;
constexpr double kFitGain = 0.1;
// Meshes with more vertices keep the asked frequency: a fit costs eleven whole patterns (knot2's line field,
// 5,760 vertices: 641 ms natively, 1.0 s in wasm under node; fitted, refined_elephant's, 44,460 vertices,
// made its export take 41 s against 5.7 s).
constexpr int32_t kFitMaxVertices = 12000;

// Whether a stripe pattern can cross a loop of the surface: a handle, or a second boundary loop (a tube).
bool hasLoops(const MeshTopology& t);

// How well a pattern's stripes follow the field: its branch faces where the field has no singularity, then
// the area mean of the angle between each other face's phase gradient (psi's, turned by `turn` where it has
// one: StripePattern::phaseTurn) and the field's growth direction there, over families.
struct FitScore {
  int32_t breaks = 0;
  double degrees = 0;
  // Fewer breaks, or a tenth less angle at least: a factor further from 1 is taken only where it pays (on
  // refined_elephant-5500, genus 3 with 38 singularities, one 0.4 % better by this score read 0.1 degrees
  // worse on the exported texture); candidates come nearest 1 first.
  bool betterThan(const FitScore& other) const {
    return breaks != other.breaks ? breaks < other.breaks : degrees < (1 - kFitGain) * other.degrees;
  }
};

// Faces left out (`near`: stripe_lift.h's nearSingularities) are not scored. breaks: the pattern's breaks
// there, which the caller may know better (BreakClosing::left).
FitScore fitScore(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g, const Families& fam,
                  const EdgeTurns& turns, const StripeOptions& o, const std::vector<double>& psi,
                  const std::vector<double>& turn, const std::vector<uint8_t>& near);

}  // namespace tvf::stripe
