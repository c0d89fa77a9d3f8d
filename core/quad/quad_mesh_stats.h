#pragma once
// What a quad mesh made from a cross field is measured by (each by its definition here, on any polygon mesh
// on the input surface): how many of its faces are quads, its irregular vertices and how close they lie to
// the field's singularities, how well its edges follow the field, how far it strays from the input surface,
// its quads' aspect ratios, flipped or degenerate faces, and its topology.
#include <cstdint>
#include <vector>

#include "dec/hodge_star.h"
#include "field/singularities.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"
#include "quad/quad_mesh.h"

namespace tvf {

struct QuadMeshStats {
  int32_t faces = 0, quads = 0, vertices = 0, edges = 0;
  double quadShare = 0;  // quads / faces
  // Vertices off the quad mesh's boundary whose number of edges is not 4.
  int32_t irregularVertices = 0, valence3 = 0, valence5 = 0;
  std::vector<int32_t> irregular;
  int32_t fieldSingularities = 0;
  // Of the irregular vertices, the share within two edge lengths (straight-line) of a field singularity, and
  // the largest such distance in edge lengths (0 when there are none).
  double irregularNearSingularity = 1, irregularFarthest = 0;
  // Field singularities within one edge length (straight line) of another: no grid of that size fits between
  // them, so where they are many the parametrization folds (a noisy field, creases as bands of features).
  int32_t crowdedSingularities = 0;
  // Per edge, the angle between its chord (projected into the input face each end lies in) and the nearest of
  // the field's directions there, the mean of the two ends: median and 90th percentile, in degrees.
  double edgeAngleMedianDeg = 0, edgeAngleP90Deg = 0;
  // The two-sided Hausdorff distance between the quad mesh (each polygon fanned from its first vertex,
  // sampled at its corners and edge midpoints) and the input (its vertices and face centroids), over the
  // input's bounding-box diagonal.
  double hausdorffRelative = 0;
  // Per quad, the mean length of one pair of opposite edges over the other's, at least 1: the median.
  double aspectMedian = 0;
  // Flipped: a polygon whose normal (Newell's) points against the input's normals at its vertices.
  // Degenerate: a polygon of area under 1e-6 edge length squared, or with a vertex twice.
  int32_t flippedFaces = 0, degenerateFaces = 0;
  int32_t boundaryEdges = 0;        // edges with one face (where the extraction left a hole)
  bool manifold = true;             // no edge with more than two faces
  bool oriented = true;             // no directed edge in two faces
  int32_t eulerCharacteristic = 0;  // V - E + F
};

// faceDirections: 3 per input face, one of the field's `symmetry` directions; singularities: the field's;
// edgeLength: the target length the distances are measured in.
QuadMeshStats measureQuadMesh(const QuadMesh& quads, const SurfaceMesh& surface, const MeshGeometry& geometry,
                              const std::vector<double>& faceDirections, int symmetry,
                              const std::vector<Singularity>& singularities, double edgeLength);

}  // namespace tvf
