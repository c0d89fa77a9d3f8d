#pragma once
// From a designed cross field to a field-aligned quad mesh: a seamless integer-grid parametrization whose
// gradients follow the field (quad/seamless_parametrization.h, after Bommes, Zimmer, Kobbelt 2009,
// "Mixed-Integer Quadrangulation"), and the mesh of its integer iso-lines (quad/quad_extraction.h, after
// Ebke, Bommes, Chen, Kobbelt 2013, "QEx"). The field is taken as it is: its singularities become the quad
// mesh's irregular vertices, and nothing of it is recomputed.
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"
#include "quad/quad_mesh.h"
#include "quad/quad_mesh_stats.h"

namespace tvf {

struct QuadRemeshOptions {
  // The quads' edge length in the model's units; 0: chosen from targetQuads (the surface's area over it).
  double edgeLength = 0;
  int64_t targetQuads = 0;
  // Vertex pairs, flat (a, b, a, b, ...): the edges the quads' edges are to follow as chains (the design's
  // sharp features), besides the boundary's, which they always follow.
  std::vector<int32_t> featureEdges;
};

struct QuadRemeshResult {
  QuadMesh mesh;
  QuadMeshStats stats;
  double edgeLength = 0;  // the one used
  // How it went: the field's cones, the cut's length, the parametrization's flipped triangles and integer
  // unknowns, the extraction's failed iso-line walks and open loops, and the stages' times.
  int32_t cones = 0, cutEdges = 0, flippedTriangles = 0, integerUnknowns = 0, roundingSolves = 0;
  int32_t unenforcedConditions = 0;  // closure equations the elimination could not keep (none expected)
  int32_t failedTraces = 0, openLoops = 0;
  int32_t filledHoles = 0;    // holes the failed walks left, closed by a polygon each
  int32_t splitPolygons = 0;  // polygons (holes closed or the grid's own) split into quads by chords
  int32_t stiffenings = 0;    // solves again with folded triangles stiffened
  // Feature curves at least an edge length long, and of those, the ones let go because the grid folded
  // beside them (features closer together than a quad).
  int32_t featureCurves = 0, releasedFeatureCurves = 0;
  double cutMs = 0, parametrizeMs = 0, extractMs = 0, measureMs = 0, totalMs = 0;
};

// Called between stages with the stage's name and the fraction of the whole done; returning false cancels
// (quadRemesh then throws RemeshCancelled).
using RemeshProgress = std::function<bool(const std::string& stage, double fraction)>;

struct RemeshCancelled : std::runtime_error {
  RemeshCancelled() : std::runtime_error("the quad remeshing was cancelled") {}
};

// faceDirections: 3 per face, one unit representative of the cross field (a Designer's faceVectors() at
// symmetry 4). Throws InputError naming the problem: a field that is not a cross field's (symmetry != 4),
// a feature pair that is not an edge, an edge length that is not positive and finite or that asks for more
// than 4 million quads, a parametrization that cannot be solved.
QuadRemeshResult quadRemesh(const SurfaceMesh& mesh, const MeshTopology& topology,
                            const MeshGeometry& geometry, const std::vector<double>& faceDirections,
                            int symmetry, const QuadRemeshOptions& options,
                            const RemeshProgress& progress = {});

}  // namespace tvf
