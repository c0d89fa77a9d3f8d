#include "direction/feature_terms.h"

#include <cmath>
#include <string>

#include "common/input_error.h"
#include "mesh/mesh_geometry.h"

namespace tvf {

std::vector<FaceDirectionTerm> featureDirectionTerms(const SurfaceMesh& mesh, const MeshTopology& t,
                                                     const FaceFrames& frames,
                                                     const std::vector<FeatureCurve>& curves, int symmetry) {
  if (symmetry < 1)
    throw InputError("a field's symmetry must be at least 1, not " + std::to_string(symmetry));
  std::vector<FaceDirectionTerm> terms;
  for (const FeatureCurve& curve : curves)
    for (size_t k = 0; k < curve.edges.size(); ++k) {
      const int32_t e = curve.edges[k];
      // The edge lies in the plane of both its faces, so its direction needs no projection; the sign turns it
      // the way the curve runs, which only N = 1 can tell.
      const Eigen::Vector3d along = double(curve.signs[k]) * edgeVector(mesh, t, e);
      for (int side = 0; side < 2; ++side) {
        const int32_t f = t.edgeFaces[2 * e + side];
        if (f < 0) continue;
        const std::complex<double> q = directionPower(frames, f, along.data(), symmetry);
        if (std::abs(q) > 0) terms.push_back({f, q});
      }
    }
  return terms;
}

}  // namespace tvf
