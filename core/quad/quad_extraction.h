#pragma once
// The quad mesh of a seamless integer-grid parametrization (after Ebke, Bommes, Chen, Kobbelt 2013, "QEx"):
// its vertices are the surface's points at integer (u, v) (the cones among them), its edges the integer
// iso-lines between them, traced through the triangles and across the cut by the transitions, and its faces
// the loops of those edges, each taking the next edge to the left.
#include <cstdint>

#include "quad/cross_field_cut.h"
#include "quad/quad_mesh.h"
#include "quad/seamless_parametrization.h"

namespace tvf {

struct QuadExtraction {
  QuadMesh mesh;
  int32_t failedTraces = 0;  // iso-line walks that found no grid point where the next one should be
  int32_t openLoops = 0;     // face loops that did not close (holes in the quad mesh)
  int32_t filledHoles = 0;   // holes closed by one polygon each
  // Polygons (holes closed, and faces the grid's own loops made where it folds) split into quads by chords
  // (quad/polygon_quadrangulation.h).
  int32_t splitPolygons = 0;
};

QuadExtraction extractQuads(const SurfaceMesh& mesh, const MeshTopology& topology, const CrossFieldCut& cut,
                            const SeamlessParametrization& parametrization);

}  // namespace tvf
