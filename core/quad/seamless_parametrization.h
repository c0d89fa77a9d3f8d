#pragma once
// A seamless integer-grid parametrization of a cut cross field (Bommes, Zimmer, Kobbelt 2009, "Mixed-Integer
// Quadrangulation"): per copy of a vertex (quad/cross_field_cut.h) a point (u, v) of one chart, whose
// gradients in each face are closest (in the area-weighted least-squares sense) to the combed field X and its
// quarter turn Y divided by the edge length, subject to the transitions across the cut: on either side of a
// cut edge the two copies differ by the field's quarter turns and an integer translation t_e,
// uv_g = R^-r_e uv_f + t_e, so the integer grid lines run on across the cut. Cones sit on grid points.
//
// The boundary's and the features' edges (the cut's isoEdges) lie on integer iso-lines: at each end the
// coordinate constant along the edge is the edge's line, an integer unknown, so that the quads' edges run
// along them (after Bommes et al. 2009, Sec. 5).
//
// The transitions' translations, the cones' positions and the iso-edges' lines are the integer unknowns; the
// conditions that the copies round each vertex come back to themselves, and that the iso-edges meeting at a
// vertex agree, are integer-coefficient equations among them, eliminated (each solved for an unknown with
// coefficient +-1) before the solve. The rest are rounded greedily: solve,
// fix the quarter of the still-free ones nearest an integer, solve again, until none is left.
#include <functional>
#include <string>
#include <vector>

#include "common/sparse_matrix.h"
#include "quad/cross_field_cut.h"

namespace tvf {

struct SeamlessParametrization {
  std::vector<double> cornerUV;   // 6 per face: each corner's (u, v), its copy's point
  std::vector<double> edgeShift;  // 2 per edge: t_e on cut edges (integers), 0 elsewhere
  int32_t flippedFaces = 0;       // faces whose (u, v) triangle is not counter-clockwise
  int32_t roundingSteps = 0;      // integers fixed one (or a batch) at a time; 0 when they were kept
  std::vector<double> integers;   // the rounded integer unknowns, to keep in a solve with other weights
};

using ParametrizationProgress = std::function<bool(double fraction)>;

// The system of one cut, made once: the integer equations eliminated, the map C from the unknowns to the
// copies' coordinates, and the pins (one regular base per component). Solved for each set of face weights
// (the remesher's stiffening rounds), which change only the energy's L in K = C^T L C.
class SeamlessSystem {
 public:
  // topology and cut must outlive the system.
  SeamlessSystem(const MeshTopology& topology, const CrossFieldCut& cut);

  int32_t integerUnknowns() const { return integerUnknowns_; }
  int32_t unenforcedConditions() const {
    return unenforced_;
  }  // no +-1 coefficient even divided by their gcd

  // edgeLength > 0: the grid's spacing on the surface. faceWeight (one per face, or empty for all 1) scales
  // each face's term: stiffer faces keep closer to the field. keptIntegers (an earlier solve's `integers`,
  // or empty): the integers kept, not rounded again: one continuous solve. progress (may be empty) is called
  // as the solve goes; returning false stops (the result then is incomplete: cornerUV empty). Throws
  // InputError when a solve fails.
  SeamlessParametrization solve(const SurfaceMesh& mesh, const MeshGeometry& geometry, double edgeLength,
                                const std::vector<double>& faceWeight = {},
                                const std::vector<double>& keptIntegers = {},
                                const ParametrizationProgress& progress = {}) const;

 private:
  const MeshTopology& t_;
  const CrossFieldCut& cut_;
  SparseMatrix C_;                // (u, v) of each copy (rows 2c, 2c + 1) from the unknowns
  SparseMatrix shift_;            // t_e of each edge (rows 2e, 2e + 1) from the unknowns (0 off the cut)
  std::vector<uint8_t> integer_;  // per unknown
  std::vector<std::pair<int32_t, double>> pinned_;
  int32_t integerUnknowns_ = 0, unenforced_ = 0;
};

// Twice the signed area of face f's (u, v) triangle (cornerUV: 6 per face): positive where it is not folded.
inline double uvTwiceArea(const std::vector<double>& cornerUV, int32_t f) {
  const double* q = &cornerUV[6 * f];
  return (q[2] - q[0]) * (q[5] - q[1]) - (q[3] - q[1]) * (q[4] - q[0]);
}

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
