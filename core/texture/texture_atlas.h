#pragma once
// The texture atlas texture synthesis runs in: a one-to-one map of the surface into [0, 1]^2.
//
// generateAtlas() cuts the surface into charts (grown over faces whose normals stay inside a cone, in order
// of distance from the seed so they come out round), flattens each by least-squares conformal maps (LSCM,
// Levy et al. 2002; CHOLMOD's supernodal Cholesky), splits any chart whose map flips a face, overlaps itself
// or stretches area too unevenly (keeping the pieces that the failed map serves), scales every chart to one
// texel density (texels per unit surface length), and packs them into the square by first fit over texel
// bitmaps of the charts (4 rotations each, `gutter` texels of exclusive border around every chart), raising
// the density until the packing no longer fits.
//
// Conventions: per face corner (u, v), 6 floats per face, in the face's own winding; texel (i, j) of an R x R
// image covers [i, i+1] x [j, j+1] / R, so v = 0 is image row 0 (as glTF samples an image).
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// What an atlas is like, measured on its own UVs at a resolution.
struct AtlasMeasures {
  int resolution = 0;
  double coverage = 0;      // share of the R^2 texel centres inside some triangle
  double overlap = 0;       // share of the covered texel centres inside two triangles or more
  int flippedFaces = 0;     // faces whose UV orientation differs from the majority of their chart
  int degenerateFaces = 0;  // faces with (near-)zero UV area but positive surface area
  // Texel density per face, sqrt(UV area R^2 / surface area), over its area-weighted median: 5th and 95th
  // percentiles (area-weighted) and the extremes.
  double densityP05 = 0, densityP95 = 0, densityMin = 0, densityMax = 0;
  double texelsPerUnitLength = 0;  // the median density itself
  // Area-weighted mean of Sander's L2 stretch of the per-face map relative to the median density (1 = no
  // anisotropy and no density change).
  double stretchL2 = 0;
  // Length of the edges between faces of two charts over the length of all edges (0 when faceChart is empty):
  // the seams a texture must be continued across.
  double seamShare = 0;
};

struct TextureAtlas {
  int resolution = 0, gutter = 0;
  std::vector<float> cornerUVs;    // 6 per face
  std::vector<int32_t> faceChart;  // chart per face; -1 for faces of zero surface area (UVs left at 0)
  int numCharts = 0;
  int splits = 0;      // charts split again because their map flipped, overlapped or stretched
  int keptPieces = 0;  // pieces of those kept on the split chart's map (not flattened again)
  int packAttempts = 0;
  double used = 0;  // share of the square given to charts: their texels and their gutters   // packings tried
                    // while searching the densest that fits
  double milliseconds = 0, chartMilliseconds = 0;  // all, and cutting + flattening alone
  AtlasMeasures measures;
};

// Throws InputError for an empty mesh, a bad index, a resolution outside [16, 8192] or a gutter outside [0,
// 16]. Charts grow across the edges of `topology`, the mesh's own (buildTopology), passed in where the caller
// already holds it.
TextureAtlas generateAtlas(const SurfaceMesh& mesh, const MeshTopology& topology, int resolution,
                           int gutterTexels);
// The same for a mesh that comes without its topology (checked first, then built here).
TextureAtlas generateAtlas(const SurfaceMesh& mesh, int resolution, int gutterTexels);

// Per texel centre of an n x n grid, how many triangles cover it (half-open edge rule, so a centre on an edge
// shared by two triangles counts once; saturates at 65535).
std::vector<uint16_t> rasterCoverage(const std::vector<float>& cornerUVs, int n);

// Measures an atlas; faceChart may be empty (then orientation is judged against the whole atlas).
AtlasMeasures measureAtlas(const SurfaceMesh& mesh, const MeshTopology& topology,
                           const std::vector<float>& cornerUVs, const std::vector<int32_t>& faceChart,
                           int resolution);

struct AtlasCheck {
  bool usable = false;
  std::string reason;
  int outside = 0, degenerate = 0, nonFinite = 0;
  double coverage = 0, overlap = 0;
};

// Whether cornerUVs (e.g. a model's TEXCOORD_0) can serve as the synthesis atlas: a one-to-one map inside
// [0, 1]^2. Synthesis needs every texel to belong to one surface point: a tiling layout (UVs outside [0, 1])
// or stacked / mirrored islands would make two regions share, and fight over, the same texels. Usable: all
// UVs finite and inside [0, 1] (1e-4 slack), < 1% of the faces with (near-)zero UV area, and < 0.5% of the
// covered texels (at `resolution`) covered twice.
AtlasCheck checkAtlasUVs(const std::vector<float>& cornerUVs, int32_t numFaces, int resolution = 512);

}  // namespace tvf
