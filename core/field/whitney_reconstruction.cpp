#include "field/whitney_reconstruction.h"

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

}  // namespace

Eigen::Vector3d whitneyVector(const SurfaceMesh& mesh, const MeshTopology& t, const double* oneForm,
                              int32_t f, const double bary[3]) {
  Eigen::Vector3d p[3];
  facePositions(mesh, f, p);
  const Eigen::Vector3d cross = (p[1] - p[0]).cross(p[2] - p[0]);
  const Eigen::Vector3d n = cross.normalized();
  double c[3], w[3];
  faceCoefficients(t, oneForm, f, c);
  whitneyWeights(c, bary, w);
  // Opposite edges: p_jk (corner 1 -> 2), p_ki (2 -> 0), p_ij (0 -> 1); perp = rotation by +pi/2 about n.
  const Eigen::Vector3d sum =
      w[0] * n.cross(p[2] - p[1]) + w[1] * n.cross(p[0] - p[2]) + w[2] * n.cross(p[1] - p[0]);
  return sum / cross.norm();
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
  const double centre[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  out.resize(3 * static_cast<size_t>(t.numFaces));
  for (int32_t f = 0; f < t.numFaces; ++f) {
    const Eigen::Vector3d u = whitneyVector(mesh, t, oneForm, f, centre);
    for (int k = 0; k < 3; ++k) out[3 * f + k] = u[k];
  }
}

void vertexVectors(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                   const double* oneForm, std::vector<double>& out) {
  out.assign(3 * static_cast<size_t>(t.numVertices), 0.0);
  std::vector<double> weight(t.numVertices, 0.0);
  for (int32_t f = 0; f < t.numFaces; ++f) {
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    const Eigen::Map<const Eigen::Vector3d> n(&g.faceNormal[3 * f]);
    // At corner i Eq. 4 reduces to (c_ij p_ki^perp - c_ki p_ij^perp) / 2|t| (the summand of Eq. 5).
    const Eigen::Vector3d perp[3] = {n.cross(p[1] - p[0]), n.cross(p[2] - p[1]), n.cross(p[0] - p[2])};
    double c[3];
    faceCoefficients(t, oneForm, f, c);
    const double scale = 1 / (2 * g.faceArea[f]);
    for (int k = 0; k < 3; ++k) {
      // Corner k: its outgoing edge is k (k -> k+1), its incoming edge k+2 (k+2 -> k).
      const Eigen::Vector3d u = scale * (c[k] * perp[(k + 2) % 3] - c[(k + 2) % 3] * perp[k]);
      const int32_t v = mesh.triangles[3 * f + k];
      const double area = g.cornerArea[3 * f + k];
      for (int d = 0; d < 3; ++d) out[3 * v + d] += area * u[d];
      weight[v] += area;
    }
  }
  for (int32_t v = 0; v < t.numVertices; ++v)
    if (weight[v] > 0)
      for (int k = 0; k < 3; ++k) out[3 * v + k] /= weight[v];
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
