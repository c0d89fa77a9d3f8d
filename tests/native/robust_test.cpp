// Numerically safe edits and refused extremes (issue: nothing a user does may lose their work or wedge the
// core). Each defect is first reproduced on the raw mechanism, then the designer's answer is checked against
// a fresh factorization of the same design.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

#include "design/design_document.h"
#include "design/designer.h"
#include "solver/factored_system.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

Eigen::VectorXd asVector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

double relativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  return (asVector(a) - asVector(b)).norm() / std::max(1e-300, asVector(b).norm());
}

bool finite(const std::vector<double>& v) {
  for (const double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

// A fresh designer holding the same design, factored once from scratch.
std::vector<double> freshSolve(const SurfaceMesh& m, const Designer& d) {
  Designer fresh(m);
  fresh.setGamma(d.gamma());
  for (const ConstraintSpec& spec : d.constraints()) fresh.add(spec);
  fresh.solve();
  return fresh.oneForm();
}

std::vector<SurfacePoint> strip(int first, int count) {
  std::vector<SurfacePoint> points;
  for (int f = first; f < first + count; ++f) points.push_back({f, {0.3, 0.3, 0.4}});
  return points;
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// The defect itself: a rank-1 update of weight 1e20 and its downdate leave nothing of the original pivots.
TEST(Robust, RawDowndateOfAHugeWeightLosesThePivot) {
  const SurfaceMesh m = icosphere(2);
  Designer d(m);
  SparseMatrix A = d.baseMatrix();
  const double scale = d.weightScale();
  FactoredSystem system;
  ASSERT_TRUE(system.factor(A));
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1, 1), before, after;
  system.solve(b, before);
  system.updateDiagonal({7}, {1e20 * scale}, false);
  system.updateDiagonal({7}, {1e20 * scale}, true);
  system.solve(b, after);
  const double error = (after - before).norm() / before.norm();
  EXPECT_FALSE(std::isfinite(error) && error < 1e-3) << "relative error " << error;
}

TEST(Robust, StrokeWeightBeyondTheRangeIsRefusedAndTheDesignKept) {
  const SurfaceMesh m = torus(24, 12, 2, 0.7);
  Designer d(m);
  d.addSource(5, 1.0);
  d.solve();
  const std::vector<double> before = d.oneForm();
  const std::string message = messageOf([&] { d.addStroke(strip(100, 10), 1.0, 1e20); });
  EXPECT_NE(message.find("weight"), std::string::npos) << message;
  EXPECT_EQ(d.constraints().size(), 1u);
  d.solve();
  EXPECT_LT(relativeDifference(d.oneForm(), before), 1e-12);
}

TEST(Robust, UndoOfTheLargestStrokeWeightEqualsAFreshSolve) {
  const SurfaceMesh m = torus(24, 12, 2, 0.7);
  Designer d(m);
  d.addSource(5, 1.0);
  const double u[3] = {0.3, 1, 0.1};
  d.addVector(40, u, 2.0);
  d.solve();
  const int id = d.addStroke(strip(100, 10), 1.0, kMaxWeight);
  d.solve();
  d.remove(id);
  d.solve();
  ASSERT_TRUE(finite(d.oneForm()));
  EXPECT_LT(relativeDifference(d.oneForm(), freshSolve(m, d)), 1e-9);
}

TEST(Robust, UndoOfTheLargestVectorWeightEqualsAFreshSolve) {
  const SurfaceMesh m = icosphere(3);
  Designer d(m);
  d.addSink(11, 2.0);
  d.solve();
  const double u[3] = {1, 0.2, 0};
  EXPECT_NE(messageOf([&] { d.addVector(30, u, 1e16); }), "");
  const int id = d.addVector(30, u, kMaxWeight);
  d.solve();
  d.remove(id);
  d.solve();
  ASSERT_TRUE(finite(d.oneForm()));
  EXPECT_LT(relativeDifference(d.oneForm(), freshSolve(m, d)), 1e-9);
}

TEST(Robust, ReweightingDownFromTheLargestWeightEqualsAFreshSolve) {
  const SurfaceMesh m = torus(24, 12, 2, 0.7);
  Designer d(m);
  d.addSource(5, 1.0);
  const int id = d.addStroke(strip(200, 12), 2.0, 1.0);
  d.solve();
  d.setWeight(id, kMaxWeight);
  d.solve();
  d.setWeight(id, 1.0);
  d.solve();
  EXPECT_LT(relativeDifference(d.oneForm(), freshSolve(m, d)), 1e-9);
  // Many ordinary undos stay within the downdate budget and keep agreeing with a fresh factor.
  for (int k = 0; k < 50; ++k) d.remove(d.addStroke(strip(10 + 3 * k, 6), 1.0, 50.0));
  d.solve();
  EXPECT_LT(relativeDifference(d.oneForm(), freshSolve(m, d)), 1e-9);
}

// Strokes at the page's weight (1e4) undone one after another, as a user undoes a session's strokes: on a
// closed genus-0 surface (no kernel, no shift) every undo is a downdate and none refactors (a downdate budget
// of 1e4 mean diagonals refactored at every second); on a torus (a kernel, shifted) the budget stays small. On
// both the field agrees with a fresh factorization of the same design all along.
TEST(Robust, UndoingManyStrokesAtThePageWeightAgreesWithAFreshSolve) {
  for (const bool shifted : {false, true}) {
    const SurfaceMesh m = shifted ? torus(24, 12, 2, 0.7) : icosphere(3);
    Designer d(m);
    d.addSource(5, 1.0);
    std::vector<int> ids;
    for (int k = 0; k < 30; ++k) {
      ids.push_back(d.addStroke(strip(10 + 9 * k, 6), 1.0, 1e4));
      d.solve();
    }
    EXPECT_EQ(d.stats().kernelShift > 0, shifted);
    const int64_t factorizations = d.stats().factorizations;
    for (int k = 29; k >= 0; --k) {
      d.remove(ids[k]);
      d.solve();
      if (k % 10 == 0) EXPECT_LT(relativeDifference(d.oneForm(), freshSolve(m, d)), 1e-9) << shifted << k;
    }
    if (!shifted) EXPECT_EQ(d.stats().factorizations, factorizations);
    EXPECT_EQ(d.stats().precisionRefactors, 0) << shifted;
  }
}

TEST(Robust, ExtremeMagnitudesAreRefusedAndLargeOnesGiveFiniteFields) {
  const SurfaceMesh m = icosphere(2);
  Designer d(m);
  d.addSource(0, 1.0);
  d.solve();
  const std::vector<double> before = d.oneForm();
  const double huge[3] = {1e308, 1e308, 0};
  EXPECT_NE(messageOf([&] { d.addVector(3, huge, 1.0); }).find("out of range"), std::string::npos);
  EXPECT_NE(messageOf([&] { d.addSource(4, 1e308); }).find("out of range"), std::string::npos);
  EXPECT_NE(messageOf([&] { d.setGamma(1e300); }).find("gamma"), std::string::npos);
  EXPECT_NE(messageOf([&] { d.addEdge(m.triangles[0], m.triangles[1], 1e300, 1.0); }), "");
  EXPECT_EQ(d.gamma(), 0.0);
  EXPECT_EQ(d.constraints().size(), 1u);
  d.solve();
  EXPECT_LT(relativeDifference(d.oneForm(), before), 1e-12);

  // The largest accepted values give finite fields that still match a fresh factorization.
  const double big[3] = {kMaxMagnitude, kMaxMagnitude, 0};
  d.addVector(3, big, 1.0);
  d.addSource(4, kMaxMagnitude);
  d.setGamma(kMaxGamma);
  d.solve();
  ASSERT_TRUE(finite(d.oneForm()));
  ASSERT_TRUE(finite(d.faceVectors()));
  EXPECT_LT(relativeDifference(d.oneForm(), freshSolve(m, d)), 1e-9);
}

TEST(Robust, DegenerateArgumentsAreRefusedWithTheirReason) {
  const SurfaceMesh m = icosphere(1);
  Designer d(m);
  EXPECT_NE(messageOf([&] { d.addEdge(3, 3, 1.0, 1.0); }).find("two different vertices"), std::string::npos);
  std::vector<SurfacePoint> zeroBary = {{0, {0, 0, 0}}, {1, {0.3, 0.3, 0.4}}};
  EXPECT_NE(messageOf([&] { d.addStroke(zeroBary, 1.0, 1.0); }).find("sum to"), std::string::npos);
  EXPECT_NE(messageOf([&] { d.addStroke(strip(0, 3), 1.0, 0.0); }).find("weight"), std::string::npos);
  EXPECT_TRUE(d.constraints().empty());
}

TEST(Robust, LargeIndicesInADesignAreReportedUnwrapped) {
  Designer d(icosphere(1));
  for (const char* text : {R"({"constraints":[{"type":"vector","face":1000000000000,"vector":[1,0,0]}]})",
                           R"({"constraints":[{"type":"source","vertex":1e12}]})",
                           R"({"constraints":[{"type":"edge","edge":[1000000000000,1],"value":1}]})",
                           R"({"constraints":[{"type":"stroke","points":[{"face":1e12,"bary":[1,0,0]},
                                                                          {"face":1,"bary":[1,0,0]}]}]})"}) {
    const std::string message = messageOf([&] { applyDesignDocument(d, nlohmann::json::parse(text)); });
    EXPECT_NE(message.find("1000000000000"), std::string::npos) << message;
    EXPECT_EQ(message.find("-727379968"), std::string::npos) << message;
  }
  const std::string nullFace = messageOf([&] {
    applyDesignDocument(
        d,
        nlohmann::json::parse(R"({"constraints":[{"type":"stroke","points":[{"face":null,"bary":null}]}]})"));
  });
  EXPECT_NE(nullFace.find("face"), std::string::npos) << nullFace;
  EXPECT_TRUE(d.constraints().empty());
}

// The factor's memory is estimated from the symbolic analysis: a limit below it refuses the mesh with a
// message naming both sizes, before any numeric work, and the designer stays usable.
TEST(Robust, AFactorBeyondTheMemoryLimitIsRefusedBeforeFactoring) {
  Designer d(icosphere(3));
  d.addSource(0, 1.0);
  d.setFactorMemoryLimit(1e5);  // 0.1 MB: the 1920-edge factor needs more
  const std::string message = messageOf([&] { d.solve(); });
  EXPECT_NE(message.find("too large"), std::string::npos) << message;
  EXPECT_NE(message.find("GB"), std::string::npos) << message;
  d.setFactorMemoryLimit(0);
  d.solve();
  EXPECT_TRUE(finite(d.oneForm()));
}

// A tetrahedron scaled by 1e100: the cotangent weights are fine but the system cannot be factored. The core
// must say so (an InputError), not crash or hand out a field.
TEST(Robust, AnUnfactorableMeshIsReportedNotCrashed) {
  SurfaceMesh m;
  m.positions = {0, 0, 0, 1e100, 0, 0, 0, 1e100, 0, 0, 0, 1e100};
  m.triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  Designer d(m);
  d.addSource(0, 1.0);
  const std::string message = messageOf([&] { d.solve(); });
  EXPECT_NE(message, "");
  EXPECT_TRUE(d.oneForm().empty());
}
