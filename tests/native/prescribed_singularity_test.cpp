// Prescribed singularities (design/prescribed_field_system.h) against truths that do not come from the
// solver's own read-out of them: the singularities the independent index count (field/singularities.h) finds
// in the field equal the prescribed set, vertex and index, on random sets summing to the Euler characteristic
// on a sphere, a torus and a genus-2 surface for N = 1, 2, 4; the field is parallel for the trivial
// connection (every dual edge's turning matches it to round-off, every cycle's holonomy a multiple of 2 pi /
// N); moving one singularity moves exactly that one; strokes bend the field without adding, moving or
// cancelling any and are followed away from them; an incomplete set leaves the rest to the field; bad input
// is refused by name with the design unchanged; sharp features are followed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <random>
#include <set>

#include "common/input_error.h"
#include "constraints/surface_walk.h"
#include "design/designer.h"
#include "direction/levi_civita_connection.h"
#include "direction/trivial_connection.h"
#include "mesh/icosphere.h"
#include "mesh/mesh_geometry.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

double principal(double angle, int symmetry) {
  const double period = 2 * kPi / symmetry;
  return angle - period * std::round(angle / period);
}

// Bumps half as high as test_meshes.h bumpySphere's.
SurfaceMesh gentleBumpySphere(int subdivisions) {
  SurfaceMesh m = icosphere(subdivisions);
  for (size_t v = 0; 3 * v < m.positions.size(); ++v) {
    double* p = &m.positions[3 * v];
    const double s = 1 + 0.08 * std::sin(3 * p[0] + 1) * std::cos(2 * p[1]) + 0.05 * std::sin(4 * p[2]);
    for (int k = 0; k < 3; ++k) p[k] *= s;
  }
  return m;
}

SurfaceMesh genusTwo() {
  return holedPlate(5, 3, {{1, 1}, {3, 1}}, 3);
}

// Singularities at random vertices, pairwise not neighbours, with indices that are multiples of 1/N summing
// to chi, each placed through the designer: a vertex it refuses (a one-ring too coarse for the index) is
// skipped.
std::map<int32_t, double> prescribeRandom(Designer& d, int symmetry, int extra, unsigned seed) {
  const MeshTopology& t = d.topology();
  std::mt19937 random(seed);
  std::uniform_int_distribution<int32_t> anyVertex(0, t.numVertices - 1);
  std::set<int32_t> blocked;
  std::map<int32_t, double> set;
  auto place = [&](int units) {
    for (;;) {
      const int32_t v = anyVertex(random);
      if (t.isBoundaryVertex[v] || t.vertexFaceCount[v] == 0 || blocked.count(v)) continue;
      try {
        d.addSingularity(v, static_cast<double>(units) / symmetry);
      } catch (const InputError&) {
        continue;
      }
      blocked.insert(v);
      for (int32_t i = t.vertexEdgeStart[v]; i < t.vertexEdgeStart[v + 1]; ++i) {
        const int32_t e = t.vertexEdgeList[i];
        blocked.insert(t.edgeVertices[2 * e]);
        blocked.insert(t.edgeVertices[2 * e + 1]);
      }
      set[v] = static_cast<double>(units) / symmetry;
      return;
    }
  };
  int total = 0;
  for (int i = 0; i < extra; ++i) {
    const int units = (i % 2 == 0) ? 1 : -1;
    place(units);
    total += units;
  }
  const int wanted = t.eulerCharacteristic() * symmetry;
  while (total != wanted) {
    const int units = total < wanted ? 1 : -1;
    place(units);
    total += units;
  }
  return set;
}

std::map<int32_t, double> found(const Designer& d) {
  std::map<int32_t, double> out;
  for (const Singularity& s : d.singularities()) out[s.vertex] = s.index;
  return out;
}

void expectSameSet(const std::map<int32_t, double>& a, const std::map<int32_t, double>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (const auto& [v, index] : a) {
    const auto it = b.find(v);
    ASSERT_TRUE(it != b.end()) << what << ": vertex " << v << " (index " << index << ") missing";
    EXPECT_NEAR(it->second, index, 1e-12) << what << ": vertex " << v;
  }
}

// The field's angle per face in the face frames the connection uses.
std::vector<double> faceAngles(const Designer& d, const FaceFrames& frames) {
  const std::vector<double>& u = d.faceVectors();
  std::vector<double> theta(u.size() / 3);
  for (size_t f = 0; f < theta.size(); ++f)
    theta[f] = std::arg(inFaceFrame(frames, static_cast<int32_t>(f), &u[3 * f]));
  return theta;
}

// The largest turning of the field against the trivial connection of `set`, modulo 2 pi / N, over every
// interior edge: 0 up to round-off for its parallel field.
double turningAgainstTrivialConnection(const Designer& d, const std::map<int32_t, double>& set,
                                       int symmetry) {
  const FaceFrames frames = faceFrames(d.mesh(), d.geometry());
  const FaceConnection c = leviCivitaConnection(d.mesh(), d.topology(), d.geometry(), frames);
  TrivialConnection trivial(d.topology(), c);
  const std::vector<double> x = trivial.rotations(holonomyTargets(d.topology(), d.geometry(), set), symmetry);
  const std::vector<double> theta = faceAngles(d, frames);
  double worst = 0;
  for (size_t k = 0; k < x.size(); ++k)
    worst = std::max(
        worst, std::abs(principal(theta[c.faceF[k]] - theta[c.faceG[k]] - c.angle[k] - x[k], symmetry)));
  return worst;
}

}  // namespace

TEST(PrescribedSingularities, RandomCompleteSetsAreExactlyTheFieldsSingularities) {
  struct Case {
    const char* name;
    SurfaceMesh mesh;
  };
  const Case cases[] = {
      {"sphere", gentleBumpySphere(3)}, {"torus", torus(40, 16, 1.0, 0.4)}, {"genus 2", genusTwo()}};
  for (const Case& c : cases)
    for (const int symmetry : {1, 2, 4})
      for (unsigned seed = 1; seed <= 3; ++seed) {
        Designer d(c.mesh);
        d.setSymmetry(symmetry);
        const std::map<int32_t, double> set = prescribeRandom(d, symmetry, 2 * static_cast<int>(seed), seed);
        d.solve();
        SCOPED_TRACE(std::string(c.name) + ", N = " + std::to_string(symmetry) + ", seed " +
                     std::to_string(seed));
        EXPECT_EQ(d.stats().singularityMode, "exact");
        expectSameSet(set, found(d), "found vs prescribed");
        for (const Singularity& s : d.singularities()) EXPECT_TRUE(s.prescribed) << s.vertex;
        EXPECT_LT(turningAgainstTrivialConnection(d, set, symmetry), 1e-9);
      }
}

TEST(PrescribedSingularities, OddAndSixFoldSymmetriesToo) {
  // N = 3 and 6 (the range is 1 to 6): random complete sets on a sphere and a torus, exactly found.
  const SurfaceMesh meshes[] = {gentleBumpySphere(3), torus(40, 16, 1.0, 0.4)};
  for (const SurfaceMesh& mesh : meshes)
    for (const int symmetry : {3, 6}) {
      Designer d(mesh);
      d.setSymmetry(symmetry);
      const std::map<int32_t, double> set = prescribeRandom(d, symmetry, 4, 21);
      d.solve();
      SCOPED_TRACE("N = " + std::to_string(symmetry) +
                   ", chi = " + std::to_string(d.topology().eulerCharacteristic()));
      EXPECT_EQ(d.stats().singularityMode, "exact");
      expectSameSet(set, found(d), "found vs prescribed");
      EXPECT_LT(turningAgainstTrivialConnection(d, set, symmetry), 1e-9);
    }
}

TEST(PrescribedSingularities, EightQuarterSingularitiesAnywhereOnASphere) {
  const SurfaceMesh mesh = icosphere(3);
  for (unsigned seed = 11; seed <= 14; ++seed) {
    Designer d(mesh);
    d.setSymmetry(4);
    const std::map<int32_t, double> set = prescribeRandom(d, 4, 0, seed);
    ASSERT_EQ(set.size(), 8u);
    d.solve();
    expectSameSet(set, found(d), "8 x +1/4");
  }
}

TEST(PrescribedSingularities, ATorusCrossFieldWithNoneHasNone) {
  // The smoothest cross field of this torus has 12 singularities (+-1/4 pairs along its inner and outer
  // equators); asked for exactly the prescribed ones, none, it has none, and is parallel.
  Designer d(torus(48, 16, 1.0, 0.35));
  d.setSymmetry(4);
  d.solve();
  EXPECT_FALSE(d.singularities().empty());
  d.setExactSingularities(true);
  d.solve();
  EXPECT_EQ(d.stats().singularityMode, "exact");
  EXPECT_TRUE(d.singularities().empty());
  EXPECT_LT(turningAgainstTrivialConnection(d, {}, 4), 1e-9);
  // A +-1/4 pair placed and removed again: the prescribed system comes and goes, the field is
  // singularity-free.
  const int32_t a = d.addSingularity(10, 0.25), b = d.addSingularity(400, -0.25);
  d.solve();
  EXPECT_EQ(d.singularities().size(), 2u);
  d.remove(a);
  d.remove(b);
  d.solve();
  EXPECT_EQ(d.stats().singularityMode, "exact");
  EXPECT_TRUE(d.singularities().empty());
  d.setExactSingularities(false);
  d.solve();
  EXPECT_EQ(d.stats().singularityMode, "none");
}

TEST(PrescribedSingularities, MovingOneMovesExactlyThatOneWithoutRefactoring) {
  Designer d(gentleBumpySphere(3));
  d.setSymmetry(4);
  const std::map<int32_t, double> set = prescribeRandom(d, 4, 2, 5);
  d.solve();
  const int64_t factorizations = d.stats().factorizations;
  // Move the first one to a vertex two rings away from every other.
  const std::vector<ConstraintSpec> specs = d.constraints();
  const ConstraintSpec moved = specs.front();
  std::map<int32_t, double> others = set;
  others.erase(moved.element);
  int32_t target = -1;
  for (int32_t v = 0; v < d.topology().numVertices && target < 0; ++v) {
    std::map<int32_t, double> trial = others;
    if (trial.count(v)) continue;
    bool far = true;
    for (const auto& [u, index] : others)
      far = far && (vertexPosition(d.mesh(), u) - vertexPosition(d.mesh(), v)).norm() > 0.3;
    if (far) target = v;
  }
  ASSERT_GE(target, 0);
  d.moveSingularity(moved.id, target);
  d.solve();
  std::map<int32_t, double> expected = others;
  expected[target] = moved.value;
  expectSameSet(expected, found(d), "after the move");
  EXPECT_EQ(d.stats().factorizations, factorizations) << "a move must only change right-hand sides";
  // Removing a +- pair leaves the others where they were.
  Designer e(gentleBumpySphere(3));
  e.setSymmetry(2);
  std::map<int32_t, double> base = prescribeRandom(e, 2, 0, 8);
  const int32_t plus = e.addSingularity(0, 0.5);
  const int32_t minus = e.addSingularity(300, -0.5);
  e.solve();
  std::map<int32_t, double> withPair = base;
  withPair[0] = 0.5;
  withPair[300] = -0.5;
  expectSameSet(withPair, found(e), "with the pair");
  e.remove(plus);
  e.remove(minus);
  e.solve();
  expectSameSet(base, found(e), "pair removed");
}

TEST(PrescribedSingularities, StrokesBendTheFieldButNeverMoveASingularity) {
  const int n = 64, m = 24;
  const SurfaceMesh mesh = torus(n, m, 1.0, 0.4);
  const std::vector<SurfacePoint> points = torusParallelStroke();
  const MeshTopology t = buildTopology(mesh);
  const StrokeWalk walk = walkStroke(mesh, t, points);
  for (const int symmetry : {1, 2, 4}) {
    Designer d(mesh);
    d.setSymmetry(symmetry);
    // A +-1/N pair well away from the stroke (vertex (i, j) is j n + i).
    const std::map<int32_t, double> set = {{12 * n + 40, 1.0 / symmetry}, {12 * n + 52, -1.0 / symmetry}};
    for (const auto& [v, index] : set) d.addSingularity(v, index);
    d.addStroke(points, 1, 1e4);
    d.solve();
    SCOPED_TRACE("N = " + std::to_string(symmetry));
    expectSameSet(set, found(d), "with a stroke");
    const FaceFrames frames = faceFrames(d.mesh(), d.geometry());
    const std::vector<double> theta = faceAngles(d, frames);
    double worst = 0;
    for (const StrokeCrossing& c : walk.crossings) {
      const double wanted = std::arg(inFaceFrame(frames, c.face, c.direction.data()));
      worst = std::max(worst, std::abs(principal(theta[c.face] - wanted, symmetry)));
    }
    EXPECT_LT(worst * 180 / kPi, 2.0);
  }
}

TEST(PrescribedSingularities, AnIncompleteSetLeavesTheRestToTheField) {
  Designer d(icosphere(3));
  d.setSymmetry(4);
  d.addSingularity(0, 0.25);
  d.addSingularity(100, 0.5);
  d.solve();
  EXPECT_EQ(d.stats().singularityMode, "free");
  EXPECT_NEAR(d.stats().freeIndex, 2 - 0.75, 1e-12);
  double total = 0, freeTotal = 0;
  int prescribedFound = 0;
  for (const Singularity& s : d.singularities()) {
    total += s.index;
    if (s.prescribed)
      ++prescribedFound;
    else
      freeTotal += s.index;
  }
  EXPECT_NEAR(total, 2.0, 1e-9);  // Poincare-Hopf
  EXPECT_EQ(prescribedFound, 2);
  EXPECT_NEAR(freeTotal, 1.25, 1e-9);
}

TEST(PrescribedSingularities, BadInputIsRefusedByNameAndChangesNothing) {
  Designer open(flatGrid(8));
  open.setSymmetry(4);
  try {
    open.addSingularity(0, 0.25);  // a corner of the grid
    FAIL() << "a boundary vertex was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("boundary vertex"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(open.constraints().empty());
  Designer d(icosphere(2));
  d.setSymmetry(4);
  EXPECT_THROW(d.addSingularity(3, 0.3), InputError);
  EXPECT_THROW(d.addSingularity(3, 0), InputError);
  const int32_t id = d.addSingularity(3, 0.25);
  try {
    d.addSingularity(3, -0.25);
    FAIL() << "a second singularity on one vertex was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("already has"), std::string::npos) << e.what();
  }
  EXPECT_THROW(d.setSymmetry(2), InputError);  // +1/4 is not a multiple of 1/2
  EXPECT_EQ(d.symmetry(), 4);
  EXPECT_THROW(d.addSource(5, 1), InputError);
  EXPECT_THROW(d.moveSingularity(id, 1 << 20), InputError);
  EXPECT_EQ(d.constraints().size(), 1u);
  EXPECT_EQ(d.constraints()[0].element, 3);
  // A vector field with a source cannot take a singularity: refused by name, the source kept.
  Designer v(icosphere(2));
  v.addSource(2, 1);
  EXPECT_THROW(v.addSingularity(7, 1), InputError);
  EXPECT_EQ(v.constraints().size(), 1u);
  v.solve();
  EXPECT_FALSE(v.oneForm().empty());
}

namespace {

// The largest angle, in degrees, between the field's nearest direction and the feature edge beside each face.
double worstFeatureAngle(const Designer& d) {
  const FaceFrames frames = faceFrames(d.mesh(), d.geometry());
  const std::vector<double> theta = faceAngles(d, frames);
  const MeshTopology& t = d.topology();
  double worst = 0;
  for (const int32_t e : d.featureEdges()) {
    const Eigen::Vector3d edge = edgeVector(d.mesh(), t, e);
    for (int side = 0; side < 2; ++side) {
      const int32_t f = t.edgeFaces[2 * e + side];
      const double along = std::arg(inFaceFrame(frames, f, edge.data()));
      // A vector field may run either way along its curve: compare as a line (N = 2) when N = 1.
      const int symmetry = std::max(2, d.symmetry());
      worst = std::max(worst, std::abs(principal(theta[f] - along, symmetry)));
    }
  }
  return worst * 180 / kPi;
}

// A square sheet folded along x = 1/2 into a roof whose two halves meet at 90 degrees.
SurfaceMesh roof() {
  SurfaceMesh m = flatGrid(12);
  for (size_t v = 0; 3 * v < m.positions.size(); ++v)
    m.positions[3 * v + 2] = 0.5 - std::abs(m.positions[3 * v] - 0.5);
  return m;
}

}  // namespace

TEST(SharpFeatures, FacesAlongFeaturesFollowThemOnABoxAndACrease) {
  // A 2 x 1 x 1 box: its 12 edges are features at 35 degrees, and a cross field follows all of them, with and
  // without its 8 corners prescribed +1/4 (each corner's defect is pi / 2).
  for (const bool corners : {false, true}) {
    Designer d(holedPlate(2, 1, {}, 4));
    d.setSymmetry(4);
    d.setFeatures(35, {}, {});
    ASSERT_GT(d.featureEdges().size(), 40u);
    if (corners)
      for (int32_t v = 0; v < d.topology().numVertices; ++v)
        if (std::abs(d.geometry().angleDefect[v] - kPi / 2) < 1e-9) d.addSingularity(v, 0.25);
    d.solve();
    SCOPED_TRACE(corners ? "corners prescribed" : "free");
    EXPECT_EQ(d.stats().featureEdges, static_cast<int32_t>(d.featureEdges().size()));
    EXPECT_LT(worstFeatureAngle(d), 0.5);
    if (corners) EXPECT_EQ(d.stats().singularityMode, "exact");
  }
  // A crease on an open sheet, every symmetry the issue names (N = 1 through the 1-form's rows).
  for (const int symmetry : {1, 2, 4}) {
    Designer d(roof());
    d.setSymmetry(symmetry);
    d.setFeatures(35, {}, {});
    ASSERT_EQ(d.featureEdges().size(), 12u);
    d.solve();
    EXPECT_LT(worstFeatureAngle(d), 0.5) << "N = " << symmetry;
    // Off: the feature is forgotten.
    d.setFeatures(0, {}, {});
    EXPECT_TRUE(d.featureEdges().empty());
  }
}

TEST(SharpFeatures, EditsByPairAndRefusals) {
  Designer d(roof());
  d.setSymmetry(2);
  d.setFeatures(35, {}, {});
  const size_t detected = d.featureEdges().size();
  const std::array<int32_t, 2> crease{d.topology().edgeVertices[2 * d.featureEdges()[0]],
                                      d.topology().edgeVertices[2 * d.featureEdges()[0] + 1]};
  d.setFeatures(35, {}, {crease});
  EXPECT_EQ(d.featureEdges().size(), detected - 1);
  EXPECT_THROW(d.setFeatures(35, {{0, 100}}, {}), InputError);  // not an edge
  EXPECT_EQ(d.featureEdges().size(), detected - 1);             // unchanged
  EXPECT_EQ(d.featureEdgesRemoved().size(), 1u);
}

TEST(PrescribedSingularities, PlacingOnePullsTheNearestFreeOneToIt) {
  // The free singularities are the smoothest field's, less the one nearest each prescription: on a bumpy
  // sphere's cross field, a +1/4 placed anywhere takes the place of the nearest natural +1/4, the others
  // stay.
  const SurfaceMesh mesh = gentleBumpySphere(3);
  Designer smooth(mesh);
  smooth.setSymmetry(4);
  smooth.solve();
  const std::map<int32_t, double> natural = found(smooth);
  ASSERT_FALSE(natural.empty());
  for (const int32_t v : {5, 200, 555}) {
    Designer d(mesh);
    d.setSymmetry(4);
    d.addSingularity(v, 0.25);
    d.solve();
    EXPECT_EQ(d.stats().singularityMode, "free");
    int32_t nearest = -1;
    double best = 1e300;
    for (const auto& [u, index] : natural)
      if (index > 0 && (vertexPosition(mesh, u) - vertexPosition(mesh, v)).norm() < best)
        best = (vertexPosition(mesh, u) - vertexPosition(mesh, v)).norm(), nearest = u;
    std::map<int32_t, double> expected = natural;
    expected[nearest] -= 0.25;
    if (std::abs(expected[nearest]) < 1e-12) expected.erase(nearest);
    expected[v] += 0.25;
    expectSameSet(expected, found(d), "one placed");
    for (const Singularity& s : d.singularities()) EXPECT_EQ(s.prescribed, s.vertex == v) << s.vertex;
  }
}

TEST(SharpFeatures, NoSingularityInsideAFeatureCurve) {
  // On a box with its creases as features: a +1/4 at a corner (where three curves meet) is the cube's own and
  // shows; inside a crease curve it is refused by name, and features that would run through a prescribed
  // vertex are refused too, the design unchanged.
  Designer d(holedPlate(1, 1, {}, 3));
  d.setSymmetry(4);
  d.setFeatures(35, {}, {});
  const MeshTopology& t = d.topology();
  std::vector<int> featureCount(t.numVertices, 0);
  for (const int32_t e : d.featureEdges()) {
    ++featureCount[t.edgeVertices[2 * e]];
    ++featureCount[t.edgeVertices[2 * e + 1]];
  }
  int32_t corner = -1, inside = -1, flat = -1;
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (featureCount[v] == 3 && corner < 0) corner = v;
    if (featureCount[v] == 2 && inside < 0) inside = v;
    if (featureCount[v] == 0 && flat < 0) flat = v;
  }
  ASSERT_TRUE(corner >= 0 && inside >= 0 && flat >= 0);
  try {
    d.addSingularity(inside, 0.25);
    FAIL() << "a singularity inside a feature curve was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("feature curve"), std::string::npos) << e.what();
  }
  d.addSingularity(corner, 0.25);
  d.solve();
  bool shown = false;
  for (const Singularity& s : d.singularities()) shown = shown || (s.vertex == corner && s.prescribed);
  EXPECT_TRUE(shown);
  EXPECT_TRUE(d.stats().warnings.empty()) << d.stats().warnings.front();
  d.setFeatures(0, {}, {});
  d.addSingularity(inside, 0.25);
  const size_t before = d.featureEdges().size();
  EXPECT_THROW(d.setFeatures(35, {}, {}), InputError);
  EXPECT_EQ(d.featureEdges().size(), before);
}

TEST(PrescribedSingularities, AUnitVectorFieldHasNoOneFormToDecompose) {
  Designer d(icosphere(2));
  d.addSingularity(3, 1);
  d.addSingularity(30, 1);
  d.solve();
  EXPECT_TRUE(d.oneForm().empty());
  try {
    d.hodgeDecomposition();
    FAIL() << "decomposed a field without a 1-form";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("prescribed singularities"), std::string::npos) << e.what();
  }
}

TEST(PrescribedSingularities, TheSmoothestFieldMadeLaterLeavesTheAngleFactorAlone) {
  // A prescription seeded from the field shown (so the smoothest field's system is not made then), then a
  // second stroke: the free singularities need the smoothest field of the design again, and making its system
  // must not refactor the angle field, whose factor takes the stroke as an update.
  const SurfaceMesh mesh = torus(64, 24, 1.0, 0.4);
  Designer d(mesh);
  d.setSymmetry(4);
  const std::vector<SurfacePoint> stroke = torusParallelStroke();
  d.addStroke(stroke, 1, 1e2);
  d.solve();
  d.addSingularity(12 * 64 + 40, 0.25);  // incomplete: chi = 0 needs a -1/4 somewhere
  d.solve();
  ASSERT_EQ(d.stats().singularityMode, "free");
  const int64_t factorizations = d.stats().factorizations;
  ASSERT_EQ(factorizations, 1);
  d.addStroke({stroke.begin() + 4, stroke.end()}, 1, 1e2);
  d.solve();
  EXPECT_EQ(d.stats().factorizations, factorizations);
  EXPECT_EQ(d.stats().singularityMode, "free");
}
