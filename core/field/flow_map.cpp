#include "field/flow_map.h"

#include <Eigen/Core>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "field/whitney_reconstruction.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

constexpr uint8_t kUncovered = 0, kInside = 1, kGutter = 2;

struct TexelBox {
  int x0, x1, y0, y1;
};

// Texel centres (x + 0.5) / size that can fall inside the triangle.
TexelBox texelBox(const Eigen::Vector2d q[3], int size) {
  const auto lo = [&](double t) { return std::max(0, static_cast<int>(std::floor(t * size - 0.5))); };
  const auto hi = [&](double t) { return std::min(size - 1, static_cast<int>(std::ceil(t * size - 0.5))); };
  const double u0 = std::min({q[0].x(), q[1].x(), q[2].x()}), u1 = std::max({q[0].x(), q[1].x(), q[2].x()});
  const double v0 = std::min({q[0].y(), q[1].y(), q[2].y()}), v1 = std::max({q[0].y(), q[1].y(), q[2].y()});
  return {lo(u0), hi(u1), lo(v0), hi(v1)};
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// The face's linear maps of tangent vectors: to UV (the differential of the atlas, J = D G^-1 E^T with E
// the edge vectors, D their UV images, G = E^T E) and to its orthonormal UV tangent frame (T along dp/du,
// B = N x T, negated where the chart is mirrored).
struct FaceMaps {
  Eigen::Matrix<double, 2, 3> toUV;
  Eigen::Matrix<double, 2, 3> toFrame;
};

FaceMaps faceMaps(const SurfaceMesh& mesh, int32_t f, const Eigen::Vector2d q[3], double twiceArea) {
  Eigen::Vector3d p[3];
  facePositions(mesh, f, p);
  Eigen::Matrix<double, 3, 2> E;
  E << p[1] - p[0], p[2] - p[0];
  Eigen::Matrix2d D;
  D << q[1] - q[0], q[2] - q[0];
  FaceMaps maps;
  maps.toUV = D * (E.transpose() * E).inverse() * E.transpose();
  const Eigen::Vector2d d1 = q[1] - q[0], d2 = q[2] - q[0];
  const Eigen::Vector3d t = ((E.col(0) * d2.y() - E.col(1) * d1.y()) / twiceArea).normalized();
  const Eigen::Vector3d b = faceNormalArea(p).normal.cross(t) * (twiceArea > 0 ? 1.0 : -1.0);
  maps.toFrame << t.transpose(), b.transpose();
  return maps;
}

void rasterizeFace(const SurfaceMesh& mesh, const float* cornerUVs, const FaceFieldSampler& sample, int32_t f,
                   FlowFrame frame, FlowField& field) {
  const float* uv = &cornerUVs[6 * f];
  const Eigen::Vector2d q[3] = {{uv[0], uv[1]}, {uv[2], uv[3]}, {uv[4], uv[5]}};
  const double twiceArea = cross2(q[1] - q[0], q[2] - q[0]);  // signed: mirrored charts are fine
  if (twiceArea == 0) return;
  const FaceMaps maps = faceMaps(mesh, f, q, twiceArea);
  const int n = field.size;
  const TexelBox box = texelBox(q, n);
  // Texel centres on a shared edge belong to both faces; the field's tangential part is continuous there.
  constexpr double kEdgeTolerance = 1e-12;
  for (int y = box.y0; y <= box.y1; ++y) {
    for (int x = box.x0; x <= box.x1; ++x) {
      const Eigen::Vector2d p((x + 0.5) / n, (y + 0.5) / n);
      const double bary[3] = {cross2(q[1] - p, q[2] - p) / twiceArea, cross2(q[2] - p, q[0] - p) / twiceArea,
                              cross2(q[0] - p, q[1] - p) / twiceArea};
      if (bary[0] < -kEdgeTolerance || bary[1] < -kEdgeTolerance || bary[2] < -kEdgeTolerance) continue;
      const Eigen::Vector3d u = sample(f, bary);
      const Eigen::Vector2d d = frame == FlowFrame::Texture ? maps.toUV * u : maps.toFrame * u;
      const double length = d.norm();
      const std::size_t texel = static_cast<std::size_t>(y) * n + x;
      field.direction[2 * texel] = length > 0 ? static_cast<float>(d.x() / length) : 0.0f;
      field.direction[2 * texel + 1] = length > 0 ? static_cast<float>(d.y() / length) : 0.0f;
      field.magnitude[texel] = static_cast<float>(u.norm());
      field.coverage[texel] = kInside;
    }
  }
}

// One ring of gutter: every uncovered texel next to a covered one takes the mean of its covered neighbours.
void dilateOnce(FlowField& field) {
  const int n = field.size;
  const std::vector<uint8_t> before = field.coverage;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const std::size_t texel = static_cast<std::size_t>(y) * n + x;
      if (before[texel] != kUncovered) continue;
      double du = 0, dv = 0, magnitude = 0;
      int count = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= n || ny >= n) continue;
          const std::size_t other = static_cast<std::size_t>(ny) * n + nx;
          if (before[other] == kUncovered) continue;
          du += field.direction[2 * other];
          dv += field.direction[2 * other + 1];
          magnitude += field.magnitude[other];
          ++count;
        }
      }
      if (count == 0) continue;
      const double length = std::hypot(du, dv);
      field.direction[2 * texel] = length > 0 ? static_cast<float>(du / length) : 0.0f;
      field.direction[2 * texel + 1] = length > 0 ? static_cast<float>(dv / length) : 0.0f;
      field.magnitude[texel] = static_cast<float>(magnitude / count);
      field.coverage[texel] = kGutter;
    }
  }
}

uint16_t quantize(double unit, double maxValue) {
  return static_cast<uint16_t>(std::lround(std::clamp(unit, 0.0, 1.0) * maxValue));
}

}  // namespace

FlowMapConvention flowMapConventionFromName(const std::string& name) {
  if (name == "gltf") return FlowMapConvention::Gltf;
  if (name == "opengl") return FlowMapConvention::OpenGl;
  throw InputError("unknown flow map convention \"" + name + "\" (expected gltf or opengl)");
}

void requireUnitSquareUVs(const std::vector<float>& cornerUVs, int32_t numFaces) {
  if (cornerUVs.empty()) throw InputError("the mesh has no texture coordinates (TEXCOORD_0) for a flow map");
  if (cornerUVs.size() != static_cast<std::size_t>(numFaces) * 6) {
    throw InputError("texture coordinates: expected 6 per face, got " + std::to_string(cornerUVs.size()));
  }
  for (std::size_t i = 0; i < cornerUVs.size(); ++i) {
    const float t = cornerUVs[i];
    if (!std::isfinite(t) || t < -1e-4f || t > 1.0f + 1e-4f) {
      throw InputError("texture coordinates of face " + std::to_string(i / 6) +
                       " lie outside the unit square (a tiling UV layout, not an atlas)");
    }
  }
}

FlowField rasterizeFlowField(const SurfaceMesh& mesh, const MeshTopology& topology, const float* cornerUVs,
                             const double* oneForm, int size, int gutterTexels, FlowFrame frame) {
  const FaceFieldSampler whitney = [&](int32_t f, const double bary[3]) {
    return whitneyVector(mesh, topology, oneForm, f, bary);
  };
  return rasterizeFlowField(mesh, topology, cornerUVs, whitney, size, gutterTexels, frame);
}

FlowField rasterizeFlowField(const SurfaceMesh& mesh, const MeshTopology& topology, const float* cornerUVs,
                             const FaceFieldSampler& sample, int size, int gutterTexels, FlowFrame frame) {
  if (size < 1 || size > 8192) throw InputError("flow map size must be 1..8192, got " + std::to_string(size));
  if (gutterTexels < 0 || gutterTexels > 64) throw InputError("gutter must be 0..64 texels");
  FlowField field;
  field.size = size;
  const std::size_t texels = static_cast<std::size_t>(size) * size;
  field.direction.assign(2 * texels, 0.0f);
  field.magnitude.assign(texels, 0.0f);
  field.coverage.assign(texels, kUncovered);
  for (int32_t f = 0; f < topology.numFaces; ++f)
    rasterizeFace(mesh, cornerUVs, sample, f, frame, field);
  for (std::size_t t = 0; t < texels; ++t) {
    if (field.coverage[t] != kInside) continue;
    field.maxMagnitude = std::max(field.maxMagnitude, field.magnitude[t]);
    ++field.coveredTexels;
  }
  for (int ring = 0; ring < gutterTexels; ++ring) dilateOnce(field);
  return field;
}

std::vector<uint16_t> encodeFlowMap(const FlowField& field, FlowMapConvention convention, int bits) {
  if (bits != 8 && bits != 16) throw InputError("flow map bits must be 8 or 16, got " + std::to_string(bits));
  const double maxValue = bits == 8 ? 255.0 : 65535.0;
  const double vSign = convention == FlowMapConvention::Gltf ? 1.0 : -1.0;
  const std::size_t texels = field.coverage.size();
  std::vector<uint16_t> rgba(4 * texels, 0);
  const uint16_t zero = quantize(0.5, maxValue);
  for (std::size_t t = 0; t < texels; ++t) {
    if (field.coverage[t] == kUncovered) {
      // No flow (R = G = 0.5) for shaders that ignore alpha.
      rgba[4 * t] = rgba[4 * t + 1] = zero;
      continue;
    }
    const double b = field.maxMagnitude > 0 ? field.magnitude[t] / field.maxMagnitude : 0.0;
    rgba[4 * t] = quantize(0.5 + 0.5 * field.direction[2 * t], maxValue);
    rgba[4 * t + 1] = quantize(0.5 + vSign * 0.5 * field.direction[2 * t + 1], maxValue);
    rgba[4 * t + 2] = quantize(b, maxValue);
    rgba[4 * t + 3] = static_cast<uint16_t>(maxValue);
  }
  return rgba;
}

}  // namespace tvf
