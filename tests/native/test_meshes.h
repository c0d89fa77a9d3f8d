#pragma once
// Meshes made in code, with known topology and geometry, for the native tests.
#include <string>
#include <vector>

#include "constraints/constraint_spec.h"
#include "mesh/icosphere.h"  // icosphere(): core's, the one the wasm warm-up designs on
#include "mesh/surface_mesh.h"

namespace tvf::testing {

// n x n squares of size `size` in the z = 0 plane, each split into two triangles; alternate diagonals when
// `regular` is false so the mesh is not a regular valence-6 grid.
SurfaceMesh flatGrid(int n, double size = 1.0, bool alternate = false);
// Flat annulus with `rings` x `sectors` quads, radii r0 < r1.
SurfaceMesh flatAnnulus(int rings, int sectors, double r0, double r1);
// Torus of revolution, valence 6 everywhere.
SurfaceMesh torus(int n, int m, double R, double r);
// icosphere(subdivisions) with smooth random bumps: curved everywhere, no symmetry to make a field's
// indices come out whole.
SurfaceMesh bumpySphere(int subdivisions = 3);
// The mesh as an OFF file's text, positions to 17 digits (what the CLI's tests hand it).
std::string offText(const SurfaceMesh& m);
// Surface of a one-voxel-thick plate of width x depth cells with a hole at every listed cell, each unit face
// split into k x k quads: genus = number of holes.
SurfaceMesh holedPlate(int width, int depth, const std::vector<std::pair<int, int>>& holes, int k);
// A stroke along a parallel of torus(n, m, ...) (quad (i, j) is faces 2 (j n + i) and +1): 25 points from 2
// to 14 quads along the first strip, at 0.3 of its height.
std::vector<SurfacePoint> torusParallelStroke();
// Concatenates meshes (several components).
SurfaceMesh disjointUnion(const SurfaceMesh& a, const SurfaceMesh& b);
// Moves every vertex by a deterministic pseudo-random offset of relative size `amount` in the mesh's own
// plane (z kept) so triangles are irregular.
void jitterPlanar(SurfaceMesh& mesh, double amount, unsigned seed);

}  // namespace tvf::testing
