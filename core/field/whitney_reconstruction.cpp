#include "field/whitney_reconstruction.h"

#include <algorithm>

#include "common/thread_team.h"
#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

// The face's three 1-form values in its own orientation: c_ij, c_jk, c_ki.
void faceCoefficients(const MeshTopology& t, const double* oneForm, int32_t f, double c[3]) {
  for (int k = 0; k < 3; ++k) c[k] = t.signOf(f, k) * oneForm[t.edgeOf(f, k)];
}

// The weights of p_jk^perp, p_ki^perp, p_ij^perp in Eq. 4.
void whitneyWeights(const double c[3], const double a[3], double w[3]) {
  const double cij = c[0], cjk = c[1], cki = c[2];
  w[0] = cki * a[2] - cij * a[1];
  w[1] = cij * a[0] - cjk * a[2];
  w[2] = cjk * a[1] - cki * a[0];
}

// Eq. 4 in face f for the face's own 1-form values c: p_jk^perp / 2|t| is grad(lambda_i), and so on.
Eigen::Vector3d whitneyVectorOf(const SurfaceMesh& mesh, int32_t f, const double c[3], const double bary[3]) {
  Eigen::Vector3d p[3], grad[3];
  facePositions(mesh, f, p);
  barycentricGradients(p, grad);
  double w[3];
  whitneyWeights(c, bary, w);
  return w[0] * grad[0] + w[1] * grad[1] + w[2] * grad[2];
}

}  // namespace

Eigen::Vector3d whitneyVector(const SurfaceMesh& mesh, const MeshTopology& t, const double* oneForm,
                              int32_t f, const double bary[3]) {
  double c[3];
  faceCoefficients(t, oneForm, f, c);
  return whitneyVectorOf(mesh, f, c, bary);
}

Eigen::Vector2d whitneyTextureVector(const SurfaceMesh& mesh, const MeshTopology& t, const double* oneForm,
                                     int32_t f, const double bary[3]) {
  const float* uv = &mesh.cornerUVs[6 * f];
  const Eigen::Vector2d q[3] = {{uv[0], uv[1]}, {uv[2], uv[3]}, {uv[4], uv[5]}};
  const auto perp = [](const Eigen::Vector2d& v) { return Eigen::Vector2d(-v.y(), v.x()); };
  const Eigen::Vector2d a = q[1] - q[0], b = q[2] - q[0];
  // Signed UV area keeps the formula right for charts that are mirrored in the atlas.
  const double twiceArea = a.x() * b.y() - a.y() * b.x();
  if (twiceArea == 0) return Eigen::Vector2d::Zero();
  double c[3], w[3];
  faceCoefficients(t, oneForm, f, c);
  whitneyWeights(c, bary, w);
  return (w[0] * perp(q[2] - q[1]) + w[1] * perp(q[0] - q[2]) + w[2] * perp(q[1] - q[0])) / twiceArea;
}

void faceVectors(const SurfaceMesh& mesh, const MeshTopology& t, const double* oneForm,
                 std::vector<double>& out) {
  faceVectors(faceVectorMap(mesh, t), t, oneForm, out);
}

FaceVectorMap faceVectorMap(const SurfaceMesh& mesh, const MeshTopology& t) {
  const double centre[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  FaceVectorMap map;
  map.coefficient.resize(9 * static_cast<size_t>(t.numFaces));
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int k = 0; k < 3; ++k) {
      // Eq. 4 is linear in the face's values: its vector for the value 1 on edge k (in the edge's canonical
      // orientation) and 0 on the others.
      double c[3] = {0, 0, 0};
      c[k] = t.signOf(f, k);
      const Eigen::Vector3d u = whitneyVectorOf(mesh, f, c, centre);
      for (int d = 0; d < 3; ++d) map.coefficient[9 * static_cast<size_t>(f) + 3 * k + d] = u[d];
    }
  return map;
}

namespace {

// The reconstructions run on the solver's helper threads, in parts of faces (partBegin): a memory bound pass
// over 9 coefficients per face, 60 MB at 832k faces, after every edit.

// Parts of a pass over this many faces: one below the size where a helper's wake-up costs more than it saves,
// else two, whatever the threads (ThreadTeam runs parts without a free helper on the calling thread): the
// vertex sums are added part by part, so the parts, not the threads, fix their rounding, and the plain and
// the threaded builds give the same vectors, bit for bit.
int partsFor(int32_t faces) {
  return faces < 50000 ? 1 : 2;
}

}  // namespace

void faceVectors(const FaceVectorMap& map, const MeshTopology& t, const double* oneForm,
                 std::vector<double>& out) {
  out.resize(3 * static_cast<size_t>(t.numFaces));
  const int parts = partsFor(t.numFaces);
  ThreadTeam::shared().run(parts, [&](int part) {
    const int32_t end = partBegin(t.numFaces, part + 1, parts);
    for (int32_t f = partBegin(t.numFaces, part, parts); f < end; ++f) {
      const double* a = &map.coefficient[9 * static_cast<size_t>(f)];
      const double c0 = oneForm[t.edgeOf(f, 0)], c1 = oneForm[t.edgeOf(f, 1)], c2 = oneForm[t.edgeOf(f, 2)];
      for (int d = 0; d < 3; ++d) out[3 * f + d] = c0 * a[d] + c1 * a[3 + d] + c2 * a[6 + d];
    }
  });
}

void vertexVectors(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                   const double* oneForm, std::vector<double>& out) {
  vertexVectors(vertexVectorMap(mesh, t, g), faceVectorMap(mesh, t), mesh, t, g, oneForm, out);
}

VertexVectorMap vertexVectorMap(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g) {
  VertexVectorMap map;
  map.numVertices = t.numVertices;
  map.inverseArea.assign(t.numVertices, 0.0);
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int k = 0; k < 3; ++k) map.inverseArea[mesh.triangles[3 * f + k]] += g.cornerArea[3 * f + k];
  for (double& w : map.inverseArea) w = w > 0 ? 1.0 / w : 0.0;
  return map;
}

namespace {

// Eq. 5's sums over faces [begin, end) added into out (3 per vertex).
void addCornerVectors(const VertexVectorMap& map, const FaceVectorMap& faces, const SurfaceMesh& mesh,
                      const MeshTopology& t, const MeshGeometry& g, const double* oneForm, int32_t begin,
                      int32_t end, double* out) {
  for (int32_t f = begin; f < end; ++f) {
    // The face map's vector for edge k is s_k (grad_{k+1} - grad_k) / 3 (faceVectorMap: Eq. 4 at the
    // barycentre), so D_k = 3 s_k a_k = grad_{k+1} - grad_k, and with the gradients summing to zero,
    // grad_k = -(2 D_k + D_{k+1}) / 3.
    const double* a = &faces.coefficient[9 * static_cast<size_t>(f)];
    double D[3][3], grad[3][3], c[3];
    for (int k = 0; k < 3; ++k) {
      const double s = t.signOf(f, k);
      for (int d = 0; d < 3; ++d) D[k][d] = 3.0 * s * a[3 * k + d];
      c[k] = s * oneForm[t.edgeOf(f, k)];
    }
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) grad[k][d] = -(2.0 * D[k][d] + D[(k + 1) % 3][d]) / 3.0;
    for (int k = 0; k < 3; ++k) {
      // Corner k: Eq. 4 at lambda_k = 1 is c_k grad(lambda_{k+1}) - c_{k+2} grad(lambda_{k+2}) (the summand
      // of Eq. 5), weighted by the corner's share of its vertex's area.
      const int32_t v = mesh.triangles[3 * f + k];
      const double w = g.cornerArea[3 * f + k] * map.inverseArea[v];
      if (w == 0) continue;
      const int next = (k + 1) % 3, in = (k + 2) % 3;
      double* o = &out[3 * static_cast<size_t>(v)];
      for (int d = 0; d < 3; ++d) o[d] += w * (c[k] * grad[next][d] - c[in] * grad[in][d]);
    }
  }
}

}  // namespace

void vertexVectors(const VertexVectorMap& map, const FaceVectorMap& faces, const SurfaceMesh& mesh,
                   const MeshTopology& t, const MeshGeometry& g, const double* oneForm,
                   std::vector<double>& out, std::vector<double>& scratch) {
  const size_t n = 3 * static_cast<size_t>(map.numVertices);
  out.assign(n, 0.0);
  // Each part sums its faces into a vertex array of its own (the first into out, the others into scratch),
  // then those are added, vertex ranges in parallel: a vertex's corners lie in any part, and no two threads
  // may add to it.
  const int parts = scratch.size() >= (partsFor(t.numFaces) - 1) * n ? partsFor(t.numFaces) : 1;
  ThreadTeam& team = ThreadTeam::shared();
  team.run(parts, [&](int part) {
    double* into = part == 0 ? out.data() : scratch.data() + (part - 1) * n;
    if (part > 0) std::fill(into, into + n, 0.0);
    addCornerVectors(map, faces, mesh, t, g, oneForm, partBegin(t.numFaces, part, parts),
                     partBegin(t.numFaces, part + 1, parts), into);
  });
  if (parts == 1) return;
  const int32_t count = static_cast<int32_t>(n);
  team.run(parts, [&](int part) {
    const int32_t end = partBegin(count, part + 1, parts);
    for (int p = 1; p < parts; ++p) {
      const double* from = scratch.data() + (p - 1) * n;
      for (int32_t i = partBegin(count, part, parts); i < end; ++i) out[i] += from[i];
    }
  });
}

void vertexVectors(const VertexVectorMap& map, const FaceVectorMap& faces, const SurfaceMesh& mesh,
                   const MeshTopology& t, const MeshGeometry& g, const double* oneForm,
                   std::vector<double>& out) {
  std::vector<double> scratch((partsFor(t.numFaces) - 1) * 3 * static_cast<size_t>(map.numVertices));
  vertexVectors(map, faces, mesh, t, g, oneForm, out, scratch);
}

void textureFaceVectors(const SurfaceMesh& mesh, const MeshTopology& t, const double* oneForm,
                        std::vector<double>& out) {
  out.clear();
  if (!mesh.hasUVs()) return;
  const double centre[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  out.resize(2 * static_cast<size_t>(t.numFaces));
  for (int32_t f = 0; f < t.numFaces; ++f) {
    const Eigen::Vector2d u = whitneyTextureVector(mesh, t, oneForm, f, centre);
    out[2 * f] = u.x();
    out[2 * f + 1] = u.y();
  }
}

}  // namespace tvf
