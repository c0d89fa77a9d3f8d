#pragma once
// Sharp features: the interior edges where the surface folds by more than a threshold (the angle between
// the two faces' normals, 0 for a flat pair), plus the user's additions and minus the user's removals.
#include <array>
#include <cstdint>
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

using VertexPair = std::array<int32_t, 2>;

// Interior edges whose normals differ by more than `degrees` (0: none), ascending.
std::vector<int32_t> sharpEdges(const MeshTopology& topology, const MeshGeometry& geometry, double degrees);

// How a surface folds: its interior edges by the angle between their faces' normals. A creased surface (a
// machined part, a hard-surface model, however coarse) folds sharply along its creases and gradually, if at
// all, elsewhere; a curved one made of facets (a scan, a sculpt, a decimated character) folds gradually at
// nearly every edge, and where its facets are coarse some of its edges pass any fixed angle without being
// creases anyone would draw. Two measures tell them apart (docs/method.md has the models they were measured
// on):
// - the sharp share of the edges that fold (edges folding less than kFlatFoldDegrees tell nothing: flat
//   parts, and the edges a subdivision adds inside a facet);
// - the share of the sharp edges on long feature curves, at least kLongCurveDiagonal of the bounding box's
//   diagonal: a creased surface's creases run on, a faceted one's sharp edges come in short pieces (both
//   unchanged by a subdivision).
struct FoldProfile {
  int32_t interiorEdges = 0;   // with two faces and finite normals
  int32_t gradualEdges = 0;    // folding by more than kFlatFoldDegrees and at most kSharpFoldDegrees
  int32_t sharpEdges = 0;      // folding by more than kSharpFoldDegrees
  int32_t longCurveEdges = 0;  // sharp edges on feature curves of them at least kLongCurveDiagonal long
  double sharpShare() const {
    const int32_t folded = gradualEdges + sharpEdges;
    return folded ? static_cast<double>(sharpEdges) / folded : 0;
  }
  double longCurveShare() const { return sharpEdges ? static_cast<double>(longCurveEdges) / sharpEdges : 0; }
};
inline constexpr double kFlatFoldDegrees = 3;
inline constexpr double kSharpFoldDegrees = 35;
inline constexpr double kLongCurveDiagonal = 0.1;
// A creased surface has at least kCreasedSharpShare of sharp share with some of its sharp edges on long
// curves (kSomeLongCurveShare: noisy scans have the share, but in pieces), or most of its sharp edges on long
// curves (kCreasedLongCurveShare: a machined part of gentle curves and a few long creases). Measured on 80
// models: machined and hard-surface ones 24-100 % sharp share with 7.5-100 % on long curves, or 71-100 % on
// long curves; scans, sculpts and decimated characters under 18 % sharp share or 0.4-1.3 % on long curves,
// and under 49 % on long curves, but for a noisy scan of bones (29 %, 11 %) and coarse tubes (knot2: its
// sharp folds run along it).
inline constexpr double kCreasedSharpShare = 0.2;
inline constexpr double kSomeLongCurveShare = 0.05;
inline constexpr double kCreasedLongCurveShare = 0.6;

FoldProfile foldProfile(const SurfaceMesh& mesh, const MeshTopology& topology, const MeshGeometry& geometry);

// The feature angle a new design starts at on this surface: kSharpFoldDegrees where it is creased, 0 (no
// features) where it curves through facets.
double suggestedFeatureAngle(const FoldProfile& profile);

// sharpEdges(degrees), plus `add`, minus `remove`, ascending and without repeats. Throws InputError naming a
// pair that is not a mesh edge (or is a boundary edge: the boundary condition owns those), or an angle that
// is not a number in [0, 180].
std::vector<int32_t> featureEdges(const MeshTopology& topology, const MeshGeometry& geometry, double degrees,
                                  const std::vector<VertexPair>& add, const std::vector<VertexPair>& remove);

// Feature curves: maximal chains of feature edges through vertices where exactly two feature edges meet
// (a closed loop is one curve). Each curve's edges in walking order, with +1 where the walk runs along the
// edge's canonical orientation (lower vertex first) and -1 against it: the orientation a vector field
// (N = 1) follows along the curve.
struct FeatureCurve {
  std::vector<int32_t> edges;
  std::vector<int8_t> signs;
  bool closed = false;
};
std::vector<FeatureCurve> featureCurves(const MeshTopology& topology, const std::vector<int32_t>& edges);

}  // namespace tvf
