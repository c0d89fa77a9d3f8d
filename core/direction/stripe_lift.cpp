// SPDX-License-Identifier: GPL-2.0-or-later
#include "direction/stripe_lift.h"

#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "common/angles.h"
#include "mesh/mesh_geometry.h"

namespace tvf::stripe {

// The match for family f across edge e walked from vertex `from`.
Match walk(const MeshTopology& t, const std::vector<Match>& matches, int F, int32_t e, int32_t from, int f) {
  if (t.edgeVertices[2 * e] == from) return matches[static_cast<size_t>(e) * F + f];
  for (int g = 0; g < F; ++g) {
    const Match m = matches[static_cast<size_t>(e) * F + g];
    if (m.family == f) return {static_cast<int8_t>(g), m.sign};
  }
  return {};
}

// Family f's frequency at vertex v, for options whose vertexFrequencyScale has F a vertex (perFamily): the
// pattern's own, whose families each adapt their spacing.
double localFrequency(const StripeOptions& o, int F, int32_t v, int f) {
  return o.vertexFrequencyScale.empty()
             ? o.frequency
             : o.frequency * o.vertexFrequencyScale[static_cast<size_t>(v) * F + f];
}

// omega along a -> b for a family whose growth directions at a and b (already matched: family fa at a, fb at
// b) are ya and yb.
double advance(const SurfaceMesh& mesh, const StripeOptions& o, int F, int32_t a, int fa, int32_t b, int fb,
               const Eigen::Vector3d& ya, const Eigen::Vector3d& yb) {
  const double nu = 0.5 * (localFrequency(o, F, a, fa) + localFrequency(o, F, b, fb));
  return kTwoPi * nu * 0.5 * (ya + yb).dot(vertexPosition(mesh, b) - vertexPosition(mesh, a));
}

double liftedStep(std::complex<double> pa, std::complex<double> pb, double omega) {
  const double turn = std::arg(pb * std::conj(pa)) - omega;
  return omega + (turn - kTwoPi * std::ceil(turn / kTwoPi - 0.5));
}

FaceLift liftFace(const SurfaceMesh& mesh, const MeshTopology& t, const Families& fam, const EdgeTurns& turns,
                  const StripeOptions& o, const std::vector<double>& psi, int32_t face, int f0) {
  const int F = fam.count;
  FaceLift l;
  for (int k = 0; k < 3; ++k) l.v[k] = mesh.triangles[3 * face + k];
  l.family[0] = f0, l.sign[0] = 1;
  for (int k = 0; k < 3; ++k) {
    const Match m = walk(t, turns.matches, F, t.edgeOf(face, k), l.v[k], l.family[k]);
    l.family[k + 1] = m.family, l.sign[k + 1] = l.sign[k] * m.sign;
  }
  l.fieldSingular = l.family[3] != f0 || l.sign[3] != 1;
  l.alpha[0] = std::arg(psiAt(psi, F, l.v[0], l.family[0], l.sign[0]));
  for (int k = 0; k < 3; ++k) {
    const int32_t a = l.v[k], b = l.v[(k + 1) % 3];
    const int fb = k < 2 ? l.family[k + 1] : f0, sb = k < 2 ? l.sign[k + 1] : 1;
    const Eigen::Vector3d ya = l.sign[k] * fam.growth[static_cast<size_t>(a) * F + l.family[k]];
    const Eigen::Vector3d yb = sb * fam.growth[static_cast<size_t>(b) * F + fb];
    const double omega = advance(mesh, o, F, a, l.family[k], b, fb, ya, yb);
    l.alpha[k + 1] =
        l.alpha[k] + liftedStep(psiAt(psi, F, a, l.family[k], l.sign[k]), psiAt(psi, F, b, fb, sb), omega);
  }
  l.n = l.fieldSingular ? 0 : static_cast<int>(std::lround((l.alpha[3] - l.alpha[0]) / kTwoPi));
  return l;
}

std::vector<uint8_t> nearSingularities(const SurfaceMesh& mesh, const MeshTopology& t,
                                       const std::vector<uint8_t>& singular, double radius) {
  std::vector<Eigen::Vector3d> centroid(t.numFaces);
  std::vector<double> distance(t.numFaces, std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int32_t f = 0; f < t.numFaces; ++f) {
    Eigen::Vector3d p[3];
    facePositions(mesh, f, p);
    centroid[f] = (p[0] + p[1] + p[2]) / 3.0;
    if (singular[f]) distance[f] = 0, queue.push({0.0, f});
  }
  while (!queue.empty()) {
    const auto [d, f] = queue.top();
    queue.pop();
    if (d > distance[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const int32_t h = t.otherFace(t.edgeOf(f, k), f);
      if (h < 0) continue;
      const double dh = d + (centroid[h] - centroid[f]).norm();
      if (dh <= radius && dh < distance[h]) distance[h] = dh, queue.push({dh, h});
    }
  }
  std::vector<uint8_t> near(t.numFaces, 0);
  for (int32_t f = 0; f < t.numFaces; ++f) near[f] = std::isfinite(distance[f]);
  return near;
}

}  // namespace tvf::stripe
