#pragma once
// A seamless integer-grid parametrization of a cut cross field (Bommes, Zimmer, Kobbelt 2009, "Mixed-Integer
// Quadrangulation"): per copy of a vertex (quad/cross_field_cut.h) a point (u, v) of one chart, whose
// gradients in each face are closest (in the area-weighted least-squares sense) to the combed field X and its
// quarter turn Y divided by the edge length, subject to the transitions across the cut: on either side of a
// cut edge the two copies differ by the field's quarter turns and an integer translation t_e,
// uv_g = R^-r_e uv_f + t_e, so the integer grid lines run on across the cut. Cones sit on grid points.
//
// The transitions' translations and the cones' positions are the integer unknowns; the conditions that the
// copies round each vertex come back to themselves are integer-coefficient equations among them, eliminated
// (each solved for an unknown with coefficient +-1) before the solve. The rest are rounded greedily: solve,
// fix the quarter of the still-free ones nearest an integer, solve again, until none is left.
#include <functional>
#include <string>
#include <vector>

#include "quad/cross_field_cut.h"

namespace tvf {

struct SeamlessParametrization {
  std::vector<double> cornerUV;   // 6 per face: each corner's (u, v), its copy's point
  std::vector<double> edgeShift;  // 2 per edge: t_e on cut edges (integers), 0 elsewhere
  int32_t flippedFaces = 0;       // faces whose (u, v) triangle is not counter-clockwise
  int32_t integerUnknowns = 0;    // after the elimination
  int32_t roundingSolves = 0;
  int32_t unenforcedConditions = 0;  // closure conditions with no +-1 coefficient (none expected)
  std::vector<double> integers;      // the rounded integer unknowns, to keep in a solve with other weights
  double assembleMs = 0, factorMs = 0, schurMs = 0, roundMs = 0;
  double energy = 0;  // the final least-squares misfit, relative to the surface's area
};

using ParametrizationProgress = std::function<bool(double fraction)>;

// edgeLength > 0: the grid's spacing on the surface. faceWeight (one per face, or empty for all 1) scales
// each face's term: stiffer faces keep closer to the field (the remesher raises it where a solve folded).
// keptIntegers (an earlier result's `integers` on the same cut, or empty): the integers kept, not rounded
// again: one continuous solve. progress (may be empty) is called after each solve;
// returning false stops (the result then is incomplete: cornerUV empty). Throws InputError when a solve
// fails.
SeamlessParametrization parametrizeSeamless(const SurfaceMesh& mesh, const MeshTopology& topology,
                                            const MeshGeometry& geometry, const CrossFieldCut& cut,
                                            double edgeLength, const ParametrizationProgress& progress = {},
                                            const std::vector<double>& faceWeight = {},
                                            const std::vector<double>& keptIntegers = {});

// (a, b) turned k quarters counter-clockwise.
inline void quarterTurn2(int k, double a, double b, double& x, double& y) {
  switch (((k % 4) + 4) % 4) {
    case 0:
      x = a, y = b;
      break;
    case 1:
      x = -b, y = a;
      break;
    case 2:
      x = -a, y = -b;
      break;
    default:
      x = b, y = -a;
      break;
  }
}

}  // namespace tvf
