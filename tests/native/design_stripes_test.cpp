// A design's stripe pattern (design/design_stripes.h) and the profiles it is drawn with
// (direction/stripe_texture.h), against invariants and analytic truth: every profile reads the same where a
// line field's phase runs the other way (x -> -x + k), so a line field's representatives leave no seam; a
// grid along a vector field takes a second family across the field (its phase gradient at right angles to the
// first's, on every face of a torus); bricks and weave are drawn from a pattern at half the frequency (the
// phase gradient's length on a flat square); a cross field refuses one-family profiles by name, and bad
// options are refused before anything is computed.
#include "design/design_stripes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/input_error.h"
#include "design/designer.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "stripe_test_fields.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

const StripeProfile kProfiles[] = {StripeProfile::Stripes, StripeProfile::WoodRings, StripeProfile::GridLines,
                                   StripeProfile::Bricks, StripeProfile::Weave};

// Per face, whether its centroid lies more than `periods` periods from every face round which the field turns
// (a pattern's fieldSingular).
std::vector<uint8_t> awayFromSingularities(const SurfaceMesh& m, const StripePattern& p, double frequency,
                                           double periods) {
  const auto centroid = [&m](int32_t f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) c += vertexPosition(m, m.triangles[3 * f + k]) / 3;
    return c;
  };
  std::vector<Eigen::Vector3d> singular;
  for (int32_t f = 0; f < m.numFaces(); ++f)
    if (p.fieldSingular[f]) singular.push_back(centroid(f));
  std::vector<uint8_t> away(m.numFaces(), 0);
  for (int32_t f = 0; f < m.numFaces(); ++f) {
    double nearest = 1e300;
    for (const Eigen::Vector3d& s : singular) nearest = std::min(nearest, (centroid(f) - s).norm());
    away[f] = nearest * frequency >= periods;
  }
  return away;
}

}  // namespace

// x -> -x + k (k whole) for the first family, and for the second too where the profile reads one: the same
// value, at points that are not on a transition (where a filtered edge may round either way).
TEST(StripeProfiles, ReadTheSameWhereTheLinePhaseRunsTheOtherWay) {
  for (const StripeProfile profile : kProfiles) {
    double worst = 0;
    for (int i = 0; i < 997; ++i) {
      const double x = -3.0 + 6.0 * std::fmod(0.6180339887 * i, 1.0);
      const double y = -3.0 + 6.0 * std::fmod(0.7548776662 * i + 0.1, 1.0);
      for (const int k : {-2, -1, 0, 1, 2, 3})
        for (const double width : {0.0, 0.2, 0.9}) {
          const double base = stripeProfileValue(profile, x, y, 0.01, width);
          worst = std::max(worst, std::abs(base - stripeProfileValue(profile, -x + k, y, 0.01, width)));
          if (stripeProfileHasTwoFamilies(profile))
            worst = std::max(worst, std::abs(base - stripeProfileValue(profile, x, -y + k, 0.01, width)));
        }
    }
    EXPECT_LT(worst, 1e-9) << stripeProfileName(profile);
  }
  for (const StripeProfile profile : kProfiles)
    EXPECT_EQ(stripeProfileNamed(stripeProfileName(profile)), profile);
  EXPECT_THROW(stripeProfileNamed("plaid"), InputError);
}

// A width asked for is the dark share of a period (sampled finely, no footprint): the stripes' bands W (value
// under 1/2), wood's darkening late wood W (under 1), grid lines both ways 1 - (1 - W)^2, bricks' mortar rows
// W and head joints W / 2 of each row, 1 - (1 - W)(1 - W / 2), the weave's gaps 1 - W (value 0: each cell's
// top thread W of it wide). A width of 0 draws the profile's own.
TEST(StripeProfiles, AWidthIsTheDarkShareOfAPeriod) {
  constexpr int kSamples = 400;
  auto share = [&](StripeProfile profile, double width, double threshold) {
    int dark = 0;
    for (int i = 0; i < kSamples; ++i)
      for (int j = 0; j < kSamples; ++j) {
        const double x = (i + 0.5) / kSamples, y = (j + 0.5) / kSamples;
        dark += stripeProfileValue(profile, x, y, 0.0, width) < threshold;
      }
    return static_cast<double>(dark) / (static_cast<double>(kSamples) * kSamples);
  };
  for (const double W : {0.1, 0.3, 0.5, 0.8}) {
    EXPECT_NEAR(share(StripeProfile::Stripes, W, 0.5), W, 0.01) << W;
    EXPECT_NEAR(share(StripeProfile::WoodRings, W, 1 - 1e-9), W, 0.01) << W;
    EXPECT_NEAR(share(StripeProfile::GridLines, W, 0.5), 1 - (1 - W) * (1 - W), 0.01) << W;
    EXPECT_NEAR(share(StripeProfile::Bricks, W, 0.5), 1 - (1 - W) * (1 - 0.5 * W), 0.01) << W;
    EXPECT_NEAR(share(StripeProfile::Weave, W, 1e-9), 1 - W, 0.01) << W;
  }
  for (const StripeProfile profile : kProfiles) {
    const double own = stripeDefaultWidth(profile);
    for (int i = 0; i < 97; ++i) {
      const double x = 0.013 * i, y = 0.029 * i;
      EXPECT_EQ(stripeProfileValue(profile, x, y, 0.01), stripeProfileValue(profile, x, y, 0.01, own));
    }
  }
}

// The vertex normals are derived once per design (DesignMesh) and every pattern reads those: the same pattern
// as normals derived for it alone.
TEST(DesignStripes, ThePatternReadsTheNormalsTheDesignKeeps) {
  const SurfaceMesh m = torus(48, 18, 2.0, 0.7);
  const Designer d(m);
  EXPECT_EQ(d.vertexNormals(), vertexNormals(m));
  DesignStripes kept;
  DesignStripeOptions o;
  o.frequency = 2.0;
  const StripePattern& p =
      kept.compute(d.mesh(), d.topology(), d.geometry(), d.vertexNormals(), 1, aroundTheTube(m), o);
  StripeOptions plain;
  plain.frequency = o.frequency * stripePatternFrequencyFactor(o.profile);
  plain.adaptSpacing = o.adaptSpacing;
  plain.maxIterations = o.maxIterations;
  plain.tolerance = o.tolerance;
  const StripePattern alone = stripePattern(m, d.topology(), d.geometry(), aroundTheTube(m), plain);
  EXPECT_EQ(p.cornerPhase, alone.cornerPhase);
  EXPECT_EQ(p.branchIndex, alone.branchIndex);
}

TEST(DesignStripes, AGridAlongAVectorFieldTakesASecondFamilyAcrossIt) {
  const SurfaceMesh m = torus(96, 36, 2.0, 0.7);
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  DesignStripes stripes;
  DesignStripeOptions o;
  o.frequency = 2.0;
  o.profile = StripeProfile::GridLines;
  const StripePattern& p = stripes.compute(m, t, g, vertexNormals(m), 1, aroundTheTube(m), o);
  ASSERT_EQ(p.families, 2);
  ASSERT_EQ(p.cornerPhase.size(), 6u * m.numFaces());
  // Each family against its own truth: the first's phase grows across the field, the second's along it.
  const std::vector<double> field = aroundTheTube(m);
  double across = 0, along = 0;
  int32_t counted = 0;
  for (int32_t f = 0; f < m.numFaces(); ++f) {
    if (p.branchIndex[f] || p.branchIndex[m.numFaces() + f]) continue;
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) d += Eigen::Vector3d(&field[3 * m.triangles[3 * f + k]]);
    const Eigen::Vector3d a = phaseGradient(m, p, 0, f).normalized(),
                          b = phaseGradient(m, p, 1, f).normalized();
    across += std::asin(std::min(1.0, std::abs(a.dot(d.normalized())))) * 180 / M_PI;
    along += std::acos(std::min(1.0, std::abs(b.dot(d.normalized())))) * 180 / M_PI;
    ++counted;
  }
  ASSERT_GT(counted, m.numFaces() / 2);
  std::cout << "[ measured ] grid along a torus's field: the first family's stripes " << across / counted
            << " deg off the field, the second's " << along / counted << " deg off across it\n";
  EXPECT_LT(across / counted, 1.0);
  EXPECT_LT(along / counted, 3.0);
}

// Across the field: a vector field's one family has its phase grow along the field (its stripes cross it)
// where it grows across by default, and a grid's two families swap; a workspace each way, so going back and
// forth gives the same patterns.
TEST(DesignStripes, StripesAcrossTheFieldTurnAQuarter) {
  const SurfaceMesh m = torus(96, 36, 2.0, 0.7);
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  const std::vector<double> field = aroundTheTube(m);
  // The area-free mean angle (degrees) of a family's phase gradient from the field's direction, mod pi.
  const auto fromField = [&](const StripePattern& p, int family) {
    double sum = 0;
    int32_t counted = 0;
    for (int32_t f = 0; f < m.numFaces(); ++f) {
      if (p.branchIndex[static_cast<size_t>(family) * m.numFaces() + f]) continue;
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) d += Eigen::Vector3d(&field[3 * m.triangles[3 * f + k]]);
      const Eigen::Vector3d a = phaseGradient(m, p, family, f).normalized();
      sum += std::acos(std::min(1.0, std::abs(a.dot(d.normalized())))) * 180 / M_PI;
      ++counted;
    }
    return sum / std::max(counted, 1);
  };
  DesignStripes stripes;
  DesignStripeOptions o;
  o.frequency = 2.0;
  const StripePattern along = stripes.compute(m, t, g, vertexNormals(m), 1, field, o);
  o.across = true;
  const StripePattern across = stripes.compute(m, t, g, vertexNormals(m), 1, field, o);
  std::cout << "[ measured ] a torus's field: the phase gradient " << fromField(along, 0) << " deg from it, "
            << fromField(across, 0) << " across it\n";
  EXPECT_GT(fromField(along, 0), 87.0);  // the phase grows across the field: stripes along it
  EXPECT_LT(fromField(across, 0), 3.0);  // along it: stripes across it
  o.profile = StripeProfile::GridLines;
  const StripePattern grid = stripes.compute(m, t, g, vertexNormals(m), 1, field, o);
  ASSERT_EQ(grid.families, 2);
  EXPECT_LT(fromField(grid, 0), 3.0);
  EXPECT_GT(fromField(grid, 1), 87.0);
  // Back along it: the along workspace's pattern again (started from itself), to round-off.
  const auto largestTurn = [](const StripePattern& a, const StripePattern& b) {
    double worst = 0;
    for (size_t i = 0; i < a.cornerPhase.size(); ++i)
      worst = std::max(worst, std::abs(std::remainder(a.cornerPhase[i] - b.cornerPhase[i], 2 * M_PI)));
    return worst;
  };
  o.profile = StripeProfile::Stripes;
  o.across = false;
  EXPECT_LT(largestTurn(stripes.compute(m, t, g, vertexNormals(m), 1, field, o), along), 1e-4);
  // A cross field has both directions: across changes nothing.
  o.profile = StripeProfile::GridLines;
  DesignStripes cross;
  const StripePattern plain = cross.compute(m, t, g, vertexNormals(m), 4, field, o);
  o.across = true;
  EXPECT_LT(largestTurn(cross.compute(m, t, g, vertexNormals(m), 4, field, o), plain), 1e-4);
}

TEST(DesignStripes, BricksAndWeaveAreDrawnFromAPatternAtHalfTheFrequency) {
  const SurfaceMesh m = flatGrid(24, 1.0, true);
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  for (const StripeProfile profile : {StripeProfile::Stripes, StripeProfile::Bricks, StripeProfile::Weave}) {
    DesignStripes stripes;
    DesignStripeOptions o;
    o.frequency = 6.0;
    o.profile = profile;
    const StripePattern& p =
        stripes.compute(m, t, g, vertexNormals(m), 2, constantField(m, Eigen::Vector3d::UnitX()), o);
    const double expected = 2 * M_PI * o.frequency * stripePatternFrequencyFactor(profile);
    for (int32_t f = 0; f < m.numFaces(); f += 37) {
      const Eigen::Vector3d grad = phaseGradient(m, p, 0, f);
      EXPECT_NEAR(grad.norm(), expected, 1e-3 * expected) << stripeProfileName(profile);
      EXPECT_NEAR(std::abs(grad.normalized().y()), 1.0, 1e-6);  // across the field (x)
    }
  }
}

// The stripes along a helical field on a torus: nu Y is not closed (the helix's pitch per ring length changes
// from the inside of the torus to the outside), so at one spacing the pattern bends the stripes off the field
// to keep the spacing. The adapted spacing lets them follow it (each face's phase gradient against the field,
// area-weighted), its frequency higher on the inside.
TEST(DesignStripes, TheAdaptedSpacingLetsTheStripesFollowTheField) {
  const SurfaceMesh m = torus(96, 36, 2.0, 0.7);
  const MeshTopology t = buildTopology(m);
  const MeshGeometry g = computeMeshGeometry(m, t);
  // Half-way between around the tube and along the ring: a helix, its turn per ring length changing from the
  // inside of the torus to the outside.
  std::vector<double> field = aroundTheTube(m);
  for (int32_t v = 0; v < m.numVertices(); ++v) {
    const Eigen::Vector3d p = vertexPosition(m, v), ring = Eigen::Vector3d(-p.y(), p.x(), 0).normalized();
    const Eigen::Vector3d h = (Eigen::Vector3d(&field[3 * v]) + ring).normalized();
    for (int c = 0; c < 3; ++c) field[3 * v + c] = h[c];
  }
  const auto meanDeviation = [&](bool adapt, std::vector<double>* spacing) {
    DesignStripes stripes;
    DesignStripeOptions o;
    o.frequency = 1.5;
    o.adaptSpacing = adapt;
    const StripePattern& p = stripes.compute(m, t, g, vertexNormals(m), 1, field, o);
    if (spacing) *spacing = p.spacing;
    double sum = 0, area = 0;
    for (int32_t f = 0; f < m.numFaces(); ++f) {
      if (p.branchIndex[f]) continue;
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) d += Eigen::Vector3d(&field[3 * m.triangles[3 * f + k]]);
      const Eigen::Vector3d grad = phaseGradient(m, p, 0, f).normalized();
      sum += g.faceArea[f] * std::asin(std::min(1.0, std::abs(grad.dot(d.normalized())))) * 180 / M_PI;
      area += g.faceArea[f];
    }
    return sum / area;
  };
  std::vector<double> spacing;
  const double even = meanDeviation(false, nullptr), adapted = meanDeviation(true, &spacing);
  std::cout << "[ measured ] stripes along a helix on a torus: " << even
            << " deg off the field at one spacing, " << adapted << " deg with the spacing adapted\n";
  EXPECT_LT(adapted, 1.3);
  EXPECT_LT(adapted, 0.3 * even);
  // The frequency's factor is larger on the inside of the torus (a shorter ring, the same number of stripes).
  ASSERT_EQ(spacing.size(), static_cast<size_t>(m.numVertices()));
  double inner = 0, outer = 0;
  int nIn = 0, nOut = 0;
  for (int32_t v = 0; v < m.numVertices(); ++v) {
    const double r = vertexPosition(m, v).head<2>().norm();
    if (r < 1.5) inner += spacing[v], ++nIn;
    if (r > 2.5) outer += spacing[v], ++nOut;
  }
  EXPECT_GT(inner / nIn, 1.3 * (outer / nOut));
}

// The smoothest cross field of a bumpy sphere, as a grid: each family's stripes along its own direction of
// the field (each face's phase gradient against the nearer of the field's two lines) away from the
// field's singularities (a face farther than two periods from every face round which the field turns), and no
// stripe ends there (a face where a family's phase winds).
TEST(DesignStripes, AGridsFamiliesBothFollowTheSmoothestCrossField) {
  const SurfaceMesh m = bumpySphere(4);
  Designer d(m);
  d.setSymmetry(4);
  d.solve();
  DesignStripes stripes;
  DesignStripeOptions o;
  o.frequency = 6;
  o.profile = StripeProfile::GridLines;
  const StripePattern& p =
      stripes.compute(d.mesh(), d.topology(), d.geometry(), d.vertexNormals(), 4, d.vertexVectors(), o);
  ASSERT_EQ(p.families, 2);
  const int32_t nF = m.numFaces();
  const std::vector<uint8_t> away = awayFromSingularities(m, p, o.frequency, 2);
  int singular = 0;
  for (int32_t f = 0; f < nF; ++f) singular += p.fieldSingular[f];
  ASSERT_GT(singular, 0);
  const std::vector<double>& field = d.vertexVectors();
  double sum[2] = {0, 0}, area = 0;
  int ends[2] = {0, 0};
  for (int32_t f = 0; f < nF; ++f) {
    if (!away[f]) continue;
    Eigen::Vector3d pos[3];
    facePositions(m, f, pos);
    const auto na = faceNormalArea(pos);
    // The field's representatives at the corners, matched to the first's (a quarter turn apart at most).
    const Eigen::Vector3d first = Eigen::Vector3d(&field[3 * m.triangles[3 * f]]);
    Eigen::Vector3d dir = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d x = Eigen::Vector3d(&field[3 * m.triangles[3 * f + k]]).normalized();
      for (int turn = 0; turn < 4 && x.dot(first) < std::sqrt(0.5) - 1e-12; ++turn) x = na.normal.cross(x);
      dir += x;
    }
    const Eigen::Vector3d along = (dir - dir.dot(na.normal) * na.normal).normalized();
    const Eigen::Vector3d across = na.normal.cross(along);
    area += na.area;
    for (int k = 0; k < 2; ++k) {
      ends[k] += p.branchIndex[static_cast<size_t>(k) * nF + f] != 0;
      const Eigen::Vector3d grad = phaseGradient(m, p, k, f).normalized();
      const double toAlong = std::acos(std::min(1.0, std::abs(grad.dot(along))));
      const double toAcross = std::acos(std::min(1.0, std::abs(grad.dot(across))));
      sum[k] += na.area * std::min(toAlong, toAcross) * 180 / M_PI;
    }
  }
  ASSERT_GT(area, 0);
  std::cout << "[ measured ] the smoothest cross field of a bumpy sphere as a grid, away from its "
            << singular << " singular faces: its families " << sum[0] / area << " and " << sum[1] / area
            << " deg off the field, " << ends[0] << " and " << ends[1] << " stripe ends\n";
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(sum[k] / area, 1.0) << "family " << k;
    EXPECT_EQ(ends[k], 0) << "family " << k;
  }
}

// The phase turned where its stripes cross the field (StripeOptions::alignPhase) on the smoothest cross field
// of a bumpy sphere, against its faces' own field (StripeOptions::faceDirections): the same psi and branch
// faces, the phase still agreeing across every edge, each family nearer its direction away from the field's
// singularities (each face's phase gradient against the nearer of the face's two lines, area-weighted), and
// the spacing's spread (of the log of each face's phase rate) grown by 15 % at most.
TEST(DesignStripes, ThePhaseTurnedOntoTheFieldKeepsItsBranchPoints) {
  const SurfaceMesh m = bumpySphere(4);
  Designer d(m);
  d.setSymmetry(4);
  d.solve();
  StripeOptions o;
  o.symmetry = 4;
  o.frequency = 6;
  o.adaptSpacing = true;
  o.faceDirections = d.faceVectors();
  o.alignPhase = false;
  const StripePattern plain =
      stripePattern(m, d.topology(), d.geometry(), d.vertexNormals(), d.vertexVectors(), o);
  o.alignPhase = true;
  const StripePattern turned =
      stripePattern(m, d.topology(), d.geometry(), d.vertexNormals(), d.vertexVectors(), o);
  EXPECT_TRUE(plain.phaseTurn.empty());
  ASSERT_EQ(turned.phaseTurn.size(), 2 * static_cast<size_t>(m.numVertices()));
  EXPECT_EQ(turned.psi, plain.psi);
  EXPECT_EQ(turned.branchIndex, plain.branchIndex);
  EXPECT_EQ(turned.fieldSingular, plain.fieldSingular);
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(worstEdgeDisagreement(m, d.topology(), plain, k, 2, true), 1e-4);
    EXPECT_LT(worstEdgeDisagreement(m, d.topology(), turned, k, 2, true), 1e-4);
  }
  const int32_t nF = m.numFaces();
  const std::vector<uint8_t> away = awayFromSingularities(m, plain, o.frequency, 2);
  ASSERT_TRUE(std::find(plain.fieldSingular.begin(), plain.fieldSingular.end(), 1) !=
              plain.fieldSingular.end());
  const auto read = [&](const StripePattern& p, int k, double& spread) {
    double sum = 0, area = 0, rate = 0, rate2 = 0;
    for (int32_t f = 0; f < nF; ++f) {
      if (!away[f] || p.branchIndex[static_cast<size_t>(k) * nF + f]) continue;
      Eigen::Vector3d pos[3];
      facePositions(m, f, pos);
      const auto na = faceNormalArea(pos);
      const Eigen::Vector3d field(&d.faceVectors()[3 * f]);
      const Eigen::Vector3d along = (field - field.dot(na.normal) * na.normal).normalized();
      const Eigen::Vector3d grad = phaseGradient(m, p, k, f);
      const double toAlong = std::acos(std::min(1.0, std::abs(grad.normalized().dot(along))));
      const double toAcross = std::asin(std::min(1.0, std::abs(grad.normalized().dot(along))));
      sum += na.area * std::min(toAlong, toAcross) * 180 / M_PI;
      const double r = std::log(grad.norm());
      rate += na.area * r, rate2 += na.area * r * r, area += na.area;
    }
    spread = std::sqrt(std::max(0.0, rate2 / area - (rate / area) * (rate / area)));
    return sum / area;
  };
  for (int k = 0; k < 2; ++k) {
    double plainSpread = 0, turnedSpread = 0;
    const double before = read(plain, k, plainSpread), after = read(turned, k, turnedSpread);
    std::cout << "[ measured ] a bumpy sphere's grid, family " << k << ": " << before
              << " deg off the field, " << after << " with the phase turned; the spacing's spread "
              << plainSpread << " -> " << turnedSpread << "\n";
    EXPECT_LT(after, 0.7 * before) << "family " << k;
    EXPECT_LT(turnedSpread, 1.15 * plainSpread) << "family " << k;
  }
}

TEST(DesignStripes, BadOptionsAreRefusedByName) {
  const auto refusal = [](int symmetry, const std::string& json) {
    try {
      checkStripeOptions(symmetry, designStripeOptionsFromJson(json, symmetry));
      return std::string("accepted");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_NE(refusal(4, R"({"profile": "stripes"})").find("cross field has two"), std::string::npos);
  EXPECT_NE(refusal(4, R"({"profile": "wood"})").find("choose grid, bricks or weave"), std::string::npos);
  EXPECT_EQ(refusal(4, "{}"), "accepted");  // a cross field's default: grid lines
  EXPECT_EQ(designStripeOptionsFromJson("{}", 4).profile, StripeProfile::GridLines);
  EXPECT_EQ(designStripeOptionsFromJson("{}", 2).profile, StripeProfile::Stripes);
  EXPECT_NE(refusal(3, "{}").find("symmetry 1, 2 or 4"), std::string::npos);
  EXPECT_NE(refusal(1, R"({"frequency": 0})").find("frequency"), std::string::npos);
  EXPECT_NE(refusal(1, R"({"frequency": "x"})").find("numbers"), std::string::npos);
  EXPECT_NE(refusal(1, R"({"magnitudeSpacing": 2})").find("magnitudeSpacing"), std::string::npos);
  EXPECT_NE(refusal(1, R"({"profile": "plaid"})").find("plaid"), std::string::npos);
  EXPECT_NE(refusal(1, R"({"width": 1.5})").find("line width"), std::string::npos);
  EXPECT_NE(refusal(1, R"({"width": -0.1})").find("line width"), std::string::npos);
  EXPECT_EQ(refusal(1, R"({"width": 0.3})"), "accepted");
  EXPECT_EQ(designStripeOptionsFromJson(R"({"width": 0.3})", 1).width, 0.3);
  EXPECT_NE(refusal(1, "[1").find("not JSON"), std::string::npos);
}
