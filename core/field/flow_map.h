#pragma once
// Flow maps: the field sampled at every texel centre of a UV atlas, as engines read it from an RGBA texture
// (docs/export.md gives the exact encoding). Per texel, the surface field of Eq. 4 at the texel's
// barycentric point is taken to UV by the atlas's differential: the direction in which a point of the
// texture moves when the surface point moves along the field. (Eq. 4 evaluated with UV positions instead
// gives the field whose UV line integrals match the one-form, J^-T u rather than J u: the same direction
// only where the atlas is conformal.)
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

// gltf: G = 0.5 + 0.5 dv (v grows with the texel row, as glTF samples). opengl: G = 0.5 - 0.5 dv, for engines
// that flip v when they import glTF (Unity, Blender, Godot). The texel layout is the same for both.
enum class FlowMapConvention { Gltf, OpenGl };

FlowMapConvention flowMapConventionFromName(const std::string& name);  // "gltf" | "opengl", else InputError

// The field per texel: texel (x, y) has its centre at UV ((x + 0.5) / size, (y + 0.5) / size).
struct FlowField {
  int size = 0;
  std::vector<float> direction;  // 2 per texel: the unit texture-domain direction (du, dv); 0 where none
  std::vector<float> magnitude;  // 1 per texel: |u| of the surface field at the same surface point
  // 1 per texel: 0 uncovered, 1 inside a UV triangle, 2 filled by the gutter dilation.
  std::vector<uint8_t> coverage;
  float maxMagnitude = 0;  // over covered texels (inside triangles)
  int64_t coveredTexels = 0;
};

// Texture: (du, dv) = J u, the field in UV coordinates (flow maps). UvTangent: the field in each face's
// orthonormal UV tangent frame (T along dp/du, B = N x T, negated on mirrored faces), which is what
// KHR_materials_anisotropy's anisotropyTexture holds for normal-mapped materials.
enum class FlowFrame { Texture, UvTangent };

// Rasterizes every face's UV triangle (cornerUVs: 6 floats per face, in [0,1]^2) at texel centres, then
// dilates the charts by `gutterTexels` so bilinear lookups at chart borders read field values, not holes.
FlowField rasterizeFlowField(const SurfaceMesh& mesh, const MeshTopology& topology, const float* cornerUVs,
                             const double* oneForm, int size, int gutterTexels,
                             FlowFrame frame = FlowFrame::Texture);
// The same for any field given by its value at a barycentric point of a face (world space): e.g. a line
// field's directions combed per chart (direction/combing.h), interpolated from its corners.
using FaceFieldSampler = std::function<Eigen::Vector3d(int32_t face, const double bary[3])>;
FlowField rasterizeFlowField(const SurfaceMesh& mesh, const MeshTopology& topology, const float* cornerUVs,
                             const FaceFieldSampler& sample, int size, int gutterTexels,
                             FlowFrame frame = FlowFrame::Texture);

// RGBA samples, 4 per texel, row-major from texel row 0, each in [0, 2^bits - 1]:
// R = 0.5 + 0.5 du, G = 0.5 +/- 0.5 dv, B = |u| / max|u|, A = max on covered and gutter texels; uncovered
// texels are (0.5, 0.5, 0, 0): no flow.
std::vector<uint16_t> encodeFlowMap(const FlowField& field, FlowMapConvention convention, int bits);

// Throws InputError when the UVs cannot index a flow map at all: missing, not 6 per face, not finite, or
// outside [0,1]^2 (with the 1e-4 slack of texture/texture_atlas.h's checkAtlasUVs, which judges the rest).
void requireUnitSquareUVs(const std::vector<float>& cornerUVs, int32_t numFaces);

}  // namespace tvf
