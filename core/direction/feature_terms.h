#pragma once
// What a sharp feature asks of the field: each face beside a feature edge takes the edge's direction (for
// N = 1 oriented as the edge's feature curve runs, mesh/feature_edges.h), as a unit power value in the
// face's frame (direction/direction_constraints.h: FaceDirectionTerm), so that the line, cross or vector
// field runs along the crease (and, for N = 4, across it). Two terms where a face has two feature edges.
#include <vector>

#include "direction/direction_constraints.h"
#include "mesh/feature_edges.h"

namespace tvf {

std::vector<FaceDirectionTerm> featureDirectionTerms(const SurfaceMesh& mesh, const MeshTopology& topology,
                                                     const FaceFrames& frames,
                                                     const std::vector<FeatureCurve>& curves, int symmetry);

}  // namespace tvf
