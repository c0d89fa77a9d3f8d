#pragma once
// What the user asks for, kept verbatim so that a design can be saved and replayed exactly (the design format
// of docs/design-format.md is these fields).
#include <cstdint>
#include <vector>

namespace tvf {

// A point on the surface as the page picks it: a face and barycentric coordinates in its corner order.
struct SurfacePoint {
  int32_t face;
  double bary[3];
};

// A Singularity prescribes a line or cross field's (or a unit vector field's) index at a vertex: element is
// the vertex, value the index (a nonzero multiple of 1/N); it is a change of the field's connection
// (direction/trivial_connection.h), not a row.
enum class ConstraintKind { Stroke, Vector, Edge, Source, Sink, Vortex, Singularity };

// Strokes, vectors and edges become weighted edge rows in the matrix; sources, sinks and vortices enter only
// the right-hand side.
inline bool isEdgeKind(ConstraintKind k) {
  return k == ConstraintKind::Stroke || k == ConstraintKind::Vector || k == ConstraintKind::Edge;
}

struct ConstraintSpec {
  int32_t id = 0;
  ConstraintKind kind = ConstraintKind::Edge;
  std::vector<SurfacePoint> points;  // stroke
  int32_t element = -1;              // face (vector, vortex) or vertex (source, sink, singularity)
  int32_t edge[2] = {-1, -1};        // edge: vertex pair, value along i -> j
  double vector[3] = {0, 0, 0};
  double value = 0;  // edge: the 1-form's value; singularity: the index
  double strength = 1;  // stroke: |t|; source/sink: total flux; vortex: signed circulation
  double weight = 1;    // edge-type constraints: relative to the mean diagonal of the system matrix
};

}  // namespace tvf
