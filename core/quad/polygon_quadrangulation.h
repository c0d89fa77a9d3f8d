#pragma once
// The polygons a quad mesh's extraction closes its holes with (where the grid folded), split into quads by
// chords between their own corners. Of all the ways to split a polygon, the one kept leaves the fewest
// irregular vertices (valence other than 4, off the boundary) on it, and then the squarest corners. Every
// part is simple and counter-clockwise in the polygon's plane and faces the surface's side at each corner; a
// quad with one reflex corner (a dart) counts as one more irregular vertex, so it is taken only where it
// spares one. A hole's corners that have only two quads besides it (valence 3) are where the missing grid
// lines would have arrived, so the chords join those.
#include <cstdint>

#include "mesh/surface_mesh.h"
#include "quad/quad_mesh.h"

namespace tvf {

// The largest polygon split: a 20-gon has 246,675 quadrangulations, each weighed in O(n).
constexpr int32_t kLargestQuadrangulatedPolygon = 20;

// Splits each polygon of the mesh with 6 to kLargestQuadrangulatedPolygon corners (an odd one leaves one
// triangle among its quads) where a split is found with no more irregular vertices (darts counted) than the
// polygon has. The surface's normal at a corner is that of the input face it lies in (mesh.vertexFace).
// Vertices and positions are kept; the faces are renumbered. Returns how many were split.
int32_t quadrangulatePolygons(QuadMesh& mesh, const SurfaceMesh& surface);

}  // namespace tvf
