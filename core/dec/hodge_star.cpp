#include "dec/hodge_star.h"

#include <cmath>

#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

// Mixed Voronoi area of each corner (Meyer et al. 2002): the Voronoi piece for non-obtuse triangles, else
// half / quarter of the face so every corner gets a positive share.
void mixedCornerAreas(const Eigen::Vector3d p[3], const double cot[3], double area, double out[3]) {
  const bool obtuse[3] = {cot[0] < 0, cot[1] < 0, cot[2] < 0};
  const bool anyObtuse = obtuse[0] || obtuse[1] || obtuse[2];
  for (int c = 0; c < 3; ++c) {
    if (anyObtuse) {
      out[c] = obtuse[c] ? area / 2 : area / 4;
      continue;
    }
    const int a = (c + 1) % 3, b = (c + 2) % 3;
    out[c] = ((p[a] - p[c]).squaredNorm() * cot[b] + (p[b] - p[c]).squaredNorm() * cot[a]) / 8;
  }
}

}  // namespace

MeshGeometry computeMeshGeometry(const SurfaceMesh& mesh, const MeshTopology& t) {
  MeshGeometry g;
  const int32_t nF = t.numFaces;
  g.faceArea.resize(nF);
  g.cornerCot.resize(3 * nF);
  g.cornerArea.resize(3 * nF);
  g.star1 = Eigen::VectorXd::Zero(t.numEdges);
  g.star2.resize(nF);
  g.whitneyMass1 = Eigen::VectorXd::Zero(t.numEdges);
  g.faceNormal.resize(3 * nF);
  g.angleDefect.assign(t.numVertices, 2 * M_PI);
  Eigen::VectorXd circumcentric = Eigen::VectorXd::Zero(t.numVertices);
  Eigen::VectorXd mixed = Eigen::VectorXd::Zero(t.numVertices);
  for (int32_t f = 0; f < nF; ++f) {
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    const FaceNormalArea face = faceNormalArea(p);
    const double area = face.area;
    g.faceArea[f] = area;
    for (int k = 0; k < 3; ++k) g.faceNormal[3 * f + k] = face.normal[k];
    g.star2[f] = 1.0 / area;
    g.totalArea += area;
    double* cot = &g.cornerCot[3 * f];
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d u = p[(c + 1) % 3] - p[c], v = p[(c + 2) % 3] - p[c];
      cot[c] = cotan(u, v);
      g.angleDefect[mesh.triangles[3 * f + c]] -= std::atan2(u.cross(v).norm(), u.dot(v));
    }
    for (int c = 0; c < 3; ++c) {
      const int a = (c + 1) % 3, b = (c + 2) % 3;
      // Edge c joins corners c and a and is opposite corner b.
      g.star1[t.edgeOf(f, c)] += 0.5 * cot[b];
      const int32_t v = mesh.triangles[3 * f + c];
      circumcentric[v] += ((p[a] - p[c]).squaredNorm() * cot[b] + (p[b] - p[c]).squaredNorm() * cot[a]) / 8;
      // Whitney mass of edge (c, a): (|p_ab|^2 + |p_bc|^2 - p_ab . p_bc) / (24 |t|), with b the opposite
      // corner.
      const Eigen::Vector3d u = p[b] - p[a], w = p[c] - p[b];
      g.whitneyMass1[t.edgeOf(f, c)] += (u.squaredNorm() + w.squaredNorm() - u.dot(w)) / (24 * area);
    }
    mixedCornerAreas(p, cot, area, &g.cornerArea[3 * f]);
    for (int c = 0; c < 3; ++c) mixed[mesh.triangles[3 * f + c]] += g.cornerArea[3 * f + c];
  }
  g.star0.resize(t.numVertices);
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (t.vertexFaceCount[v] == 0) {
      g.star0[v] = 1.0;  // unused vertex: no edge touches it, any positive value keeps the algebra finite
    } else if (circumcentric[v] > 1e-12 * mixed[v]) {
      g.star0[v] = circumcentric[v];
    } else {
      g.star0[v] = mixed[v];
      ++g.positiveAreaFallbackVertices;
    }
  }
  double lengthSum = 0;
  for (int32_t e = 0; e < t.numEdges; ++e) lengthSum += edgeVector(mesh, t, e).norm();
  g.meanEdgeLength = lengthSum / std::max(1, t.numEdges);
  return g;
}

}  // namespace tvf
