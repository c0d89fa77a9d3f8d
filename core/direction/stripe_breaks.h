#pragma once
// Stripe breaks closed: the branch points a stripe pattern's eigenvector puts away from the field's
// singularities (a stripe that ends in the open, where the spacing could not follow the field's turns) taken
// out in pairs of opposite index (a dislocation pair: one stripe more on one side of the pair than on the
// other). The pair's disc gets the phase with no zero that follows the connection's advances best, its rim
// held: the extra stripe is spread over the disc as a change of spacing instead of ending in it.
#include <cstdint>
#include <vector>

#include "dec/hodge_star.h"
#include "direction/stripe_lift.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf::stripe {

struct BreakClosing {
  int32_t closed = 0;  // pairs closed
  int32_t left = 0;    // breaks still more than kBreakAwayPeriods from the field's singular faces
  bool kept = false;   // whether the closed pairs were kept (only where none is left: see closeStripeBreaks)
};

// A break counts as away from the field's singularities beyond this many periods (1 / options.frequency),
// measured across faces from the faces round which the field's representatives do not match up.
constexpr double kBreakAwayPeriods = 2.0;

// Closes psi's breaks (families x 2 per vertex, as StripePattern::psi; the faces' branch indices are read
// with liftFace) more than kBreakAwayPeriods from the field's singular faces, each with a break of opposite
// index in the same family within 12 periods that a disc holds with no other break in it, the disc at most 8
// periods round the path between them (faces only: never a singular face, never round one). psi changes only
// on the discs' inner vertices, and only where every break away from the singularities could be closed: a
// pattern that keeps some break anyway would trade direction for nothing (bunny00's grid: six pairs
// closed, three breaks left in each family, its stripes 0.3 degrees further off the field).
BreakClosing closeStripeBreaks(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                               const Families& fam, const EdgeTurns& turns, const StripeOptions& o,
                               std::vector<double>& psi);

}  // namespace tvf::stripe
