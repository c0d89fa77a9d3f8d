// SPDX-License-Identifier: GPL-2.0-or-later
// Combing a line or cross field's vertex representatives (direction/combing.h, combVertexDirections): on a
// torus whose field (around the tube) has no singularity, whatever representative each vertex starts with
// (its direction turned by a pseudo-random multiple of 2 pi / N), the combed ones agree across every edge,
// each is its own turned by a multiple of 2 pi / N, and a cross field's stripe pattern keeps its families'
// labels across every edge (a brick or weave profile then has no seam there).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "direction/combing.h"
#include "direction/representative_directions.h"
#include "direction/stripe_pattern.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "stripe_test_fields.h"
#include "test_meshes.h"

namespace {

using tvf::SurfaceMesh;

// aroundTheTube with each vertex's direction turned by 2 pi k / N, k pseudo-random, about its normal.
std::vector<double> scrambled(const SurfaceMesh& m, int symmetry, unsigned seed) {
  std::vector<double> d = tvf::testing::aroundTheTube(m);
  const std::vector<double> normals = tvf::vertexNormals(m);
  std::mt19937 rng(seed);
  for (int32_t v = 0; v < m.numVertices(); ++v) {
    const Eigen::Vector3d n(&normals[3 * v]), x(&d[3 * v]);
    const double angle = 2 * M_PI * static_cast<double>(rng() % symmetry) / symmetry;
    const Eigen::Vector3d y = std::cos(angle) * x + std::sin(angle) * n.cross(x);
    for (int k = 0; k < 3; ++k) d[3 * v + k] = y[k];
  }
  return d;
}

TEST(VertexCombing, ASingularityFreeFieldAgreesAcrossEveryEdge) {
  const SurfaceMesh m = tvf::testing::torus(48, 24, 2.0, 0.7);
  const tvf::MeshTopology t = tvf::buildTopology(m);
  const std::vector<double> normals = tvf::vertexNormals(m);
  for (const int symmetry : {2, 4}) {
    const std::vector<double> raw = scrambled(m, symmetry, 11u * symmetry);
    const std::vector<double> combed = tvf::combVertexDirections(t, normals, raw, symmetry);
    const int32_t before = tvf::disagreeingEdges(t, normals, raw, symmetry);
    std::cout << "[ measured ] N = " << symmetry << ": " << before << " of " << t.numEdges
              << " edges disagree before combing, " << tvf::disagreeingEdges(t, normals, combed, symmetry)
              << " after\n";
    EXPECT_GT(before, t.numEdges / 4);
    EXPECT_EQ(tvf::disagreeingEdges(t, normals, combed, symmetry), 0);
    double worst = 0;
    for (int32_t v = 0; v < m.numVertices(); ++v) {
      const Eigen::Vector3d a(&raw[3 * v]), b(&combed[3 * v]), n(&normals[3 * v]);
      worst = std::max({worst, std::abs(tvf::symmetricAngle(a, b, n, symmetry)), std::abs(b.norm() - 1)});
    }
    EXPECT_LT(worst, 1e-4);  // projected into the vertex's tangent plane (its discrete normal)
  }
}

// Across an edge between two regular faces, the first family's phase gradients point the same way (up to
// sign) unless the faces label the families differently (then they are at right angles).
TEST(VertexCombing, ACrossFieldsStripeFamiliesKeepTheirLabelsAcrossEveryEdge) {
  const SurfaceMesh m = tvf::testing::torus(48, 24, 2.0, 0.7);
  const tvf::MeshTopology t = tvf::buildTopology(m);
  const tvf::MeshGeometry g = tvf::computeMeshGeometry(m, t);
  tvf::StripeOptions o;
  o.symmetry = 4;
  o.frequency = 2.0;
  const tvf::StripePattern p = tvf::stripePattern(m, t, g, scrambled(m, 4, 5u), o);
  int32_t swapped = 0, compared = 0;
  for (int32_t e = 0; e < t.numEdges; ++e) {
    const int32_t f = t.edgeFaces[2 * e], h = t.edgeFaces[2 * e + 1];
    if (f < 0 || h < 0 || p.branchIndex[f] || p.branchIndex[h] || p.fieldSingular[f] || p.fieldSingular[h])
      continue;
    const Eigen::Vector3d a = tvf::testing::phaseGradient(m, p, 0, f),
                          b = tvf::testing::phaseGradient(m, p, 0, h);
    ++compared;
    swapped += std::abs(a.normalized().dot(b.normalized())) < std::sqrt(0.5);
  }
  std::cout << "[ measured ] " << swapped << " of " << compared << " edges swap the families\n";
  EXPECT_GT(compared, t.numEdges / 2);
  EXPECT_EQ(swapped, 0);
}

}  // namespace
