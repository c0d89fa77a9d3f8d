#include "quad/seamless_parametrization.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "common/input_error.h"
#include "mesh/mesh_geometry.h"
#include "quad/greedy_rounding.h"

namespace tvf {
namespace {

// A linear combination of integer unknowns with integer coefficients: (unknown, coefficient), by unknown.
using Combo = std::vector<std::pair<int32_t, int64_t>>;

Combo sum(const Combo& a, int64_t sa, const Combo& b, int64_t sb) {
  Combo out;
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].first < b[j].first)) {
      out.emplace_back(a[i].first, sa * a[i].second), ++i;
    } else if (i == a.size() || b[j].first < a[i].first) {
      out.emplace_back(b[j].first, sb * b[j].second), ++j;
    } else {
      const int64_t c = sa * a[i].second + sb * b[j].second;
      if (c) out.emplace_back(a[i].first, c);
      ++i, ++j;
    }
  }
  return out;
}

// A point (u, v) made of integer combinations.
struct ComboPoint {
  Combo u, v;
};

ComboPoint turned(int k, const ComboPoint& p) {
  switch (((k % 4) + 4) % 4) {
    case 0:
      return p;
    case 1:
      return {sum(p.v, -1, {}, 0), p.u};
    case 2:
      return {sum(p.u, -1, {}, 0), sum(p.v, -1, {}, 0)};
    default:
      return {p.v, sum(p.u, -1, {}, 0)};
  }
}

ComboPoint added(const ComboPoint& a, const ComboPoint& b, int64_t sb) {
  return {sum(a.u, 1, b.u, sb), sum(a.v, 1, b.v, sb)};
}

// Integer unknowns tied by equations sum c_i x_i = 0: each equation solved for one unknown of coefficient
// +-1 in terms of the others (substituted lazily, path-compressed).
class IntegerElimination {
 public:
  explicit IntegerElimination(int32_t n) : expression_(n), eliminated_(n, 0) {}

  Combo resolve(int32_t x) {
    if (!eliminated_[x]) return {{x, 1}};
    Combo r;
    for (const auto& [y, c] : expression_[x]) r = sum(r, 1, resolve(y), c);
    expression_[x] = r;
    return r;
  }
  Combo resolve(const Combo& c) {
    Combo r;
    for (const auto& [y, k] : c) r = sum(r, 1, resolve(y), k);
    return r;
  }
  // Returns false when the equation has no coefficient +-1 (it is then left out).
  bool add(const Combo& equation, int32_t preferBelow) {
    Combo row = resolve(equation);
    if (row.empty()) return true;
    // g (sum c_i x_i) = 0 over the integers is sum c_i x_i = 0: the last cones' conditions reduce to rows
    // of even coefficients (2 (c_a - c_b + ...) = 0), which would otherwise have no +-1 to solve for.
    int64_t g = 0;
    for (const auto& [y, c] : row) g = std::gcd(g, std::abs(c));
    for (auto& [y, c] : row) c /= g;
    int best = -1;
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (std::abs(row[i].second) != 1) continue;
      if (best < 0 || (row[i].first < preferBelow && row[best].first >= preferBelow))
        best = static_cast<int>(i);
    }
    if (best < 0) return false;
    const int32_t x = row[best].first;
    const int64_t s = row[best].second;
    Combo e;
    for (const auto& [y, c] : row)
      if (y != x) e.emplace_back(y, -s * c);
    expression_[x] = e;
    eliminated_[x] = 1;
    return true;
  }
  bool eliminated(int32_t x) const { return eliminated_[x] != 0; }

 private:
  std::vector<Combo> expression_;
  std::vector<uint8_t> eliminated_;
};

struct Layout {
  std::vector<int32_t>
      baseColumn;                 // 2 per fan: the column of its base's u and v, -1 where integer (a cone's)
  std::vector<int32_t> integerZ;  // per integer unknown: its index, -1 when eliminated
  int32_t size = 0;
};

// An integer combination's terms as triplets of row `row` over the solve's unknowns.
void addRow(std::vector<Eigen::Triplet<double>>& triplets, int32_t row, const Combo& c,
            const Layout& layout) {
  for (const auto& [x, k] : c) triplets.emplace_back(row, layout.integerZ[x], static_cast<double>(k));
}

// Component i of R^k b (turned(k, ...)) is sign * b[j]: (j, sign).
std::pair<int, int64_t> turnedComponent(int k, int i) {
  static constexpr int kFrom[4][2] = {{0, 1}, {1, 0}, {0, 1}, {1, 0}};
  static constexpr int64_t kSign[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  const int q = ((k % 4) + 4) % 4;
  return {kFrom[q][i], kSign[q][i]};
}

}  // namespace

SeamlessSystem::SeamlessSystem(const MeshTopology& t, const CrossFieldCut& cut) : t_(t), cut_(cut) {
  const int32_t numFans = static_cast<int32_t>(cut.fanTurns.size());
  const int32_t numCopies = static_cast<int32_t>(cut.copyFan.size());
  const int32_t numIso = static_cast<int32_t>(cut.isoEdges.size());
  // Integer unknowns: t_e for each cut edge, then each cone's position, then each iso-edge's line.
  std::vector<int32_t> cutIndex(t.numEdges, -1), coneIndex(numFans, -1);
  int32_t numCut = 0, numCones = 0;
  for (int32_t e = 0; e < t.numEdges; ++e)
    if (cut.cut[e]) cutIndex[e] = numCut++;
  for (int32_t fan = 0; fan < numFans; ++fan)
    if (cut.fanTurns[fan]) coneIndex[fan] = numCones++;
  const int32_t firstIso = 2 * (numCut + numCones), numIntegers = firstIso + numIso;
  auto shiftOf = [&](int32_t e) { return ComboPoint{{{2 * cutIndex[e], 1}}, {{2 * cutIndex[e] + 1, 1}}}; };
  auto coneOf = [&](int32_t fan) {
    const int32_t x = 2 * numCut + 2 * coneIndex[fan];
    return ComboPoint{{{x, 1}}, {{x + 1, 1}}};
  };

  // Each copy relative to its fan's base: quarter turns k and an integer combination.
  std::vector<int> copyTurns(numCopies, 0);
  std::vector<ComboPoint> copyShift(numCopies);
  auto across = [&](int32_t copy, int& turns, ComboPoint& shift) {
    const int32_t e = cut.copyEdge[copy], from = cut.copyFromFace[copy], prev = cut.copyPrevious[copy];
    const int r = cut.matching[e];
    if (t.edgeFaces[2 * e] == from) {
      turns = copyTurns[prev] - r;
      shift = added(turned(-r, copyShift[prev]), shiftOf(e), 1);
    } else {
      turns = copyTurns[prev] + r;
      shift = turned(r, added(copyShift[prev], shiftOf(e), -1));
    }
  };
  IntegerElimination elimination(numIntegers);
  for (int32_t fan = 0; fan < numFans; ++fan) {
    const int32_t first = cut.fanFirstCopy[fan], end = cut.fanFirstCopy[fan + 1];
    for (int32_t c = first + 1; c < end; ++c) across(c, copyTurns[c], copyShift[c]);
    if (cut.copyEdge[first] < 0) continue;
    // Back round to the first copy: R^k base + shift = base.
    int k = 0;
    ComboPoint shift;
    across(first, k, shift);
    ComboPoint condition = shift;
    if (coneIndex[fan] >= 0) condition = added(added(turned(k, coneOf(fan)), coneOf(fan), -1), shift, 1);
    for (const Combo* row : {&condition.u, &condition.v})
      if (!elimination.add(*row, 2 * numCut)) ++unenforced_;
  }

  // Iso-edges: at both ends, the copy's constant coordinate is the edge's line m, an integer. In base terms,
  // sign * base[j] + shift_i = m: a base coordinate that is an integer combination from then on (a fan with
  // both on a grid point: a corner of the features or the boundary), or, already one, an integer equation.
  std::vector<std::optional<Combo>> baseCombo(2 * numFans);
  for (int32_t fan = 0; fan < numFans; ++fan)
    if (coneIndex[fan] >= 0) baseCombo[2 * fan] = coneOf(fan).u, baseCombo[2 * fan + 1] = coneOf(fan).v;
  for (int32_t k = 0; k < numIso; ++k) {
    const CrossFieldCut::IsoEdge& iso = cut.isoEdges[k];
    const int i = iso.coordinate;
    for (int corner = 0; corner < 3; ++corner) {
      if (t.edgeOf(iso.face, corner) != iso.edge) continue;
      for (int end = 0; end < 2; ++end) {
        const int32_t copy = cut.cornerCopy[3 * iso.face + (corner + end) % 3], fan = cut.copyFan[copy];
        const auto [j, sign] = turnedComponent(copyTurns[copy], i);
        const Combo& shift = i == 0 ? copyShift[copy].u : copyShift[copy].v;
        const Combo value = sum(sum(Combo{{firstIso + k, 1}}, 1, shift, -1), sign, {}, 0);  // base[j]
        std::optional<Combo>& slot = baseCombo[2 * fan + j];
        if (!slot) {
          slot = value;
        } else if (!elimination.add(sum(*slot, 1, value, -1), 2 * numCut)) {
          ++unenforced_;
        }
      }
    }
  }

  // The unknowns: the base coordinates left continuous, then the integer unknowns left free.
  Layout layout;
  layout.baseColumn.assign(2 * numFans, -1);
  for (int32_t k = 0; k < 2 * numFans; ++k)
    if (!baseCombo[k]) layout.baseColumn[k] = layout.size++;
  layout.integerZ.assign(numIntegers, -1);
  integer_.assign(layout.size, 0);
  for (int32_t x = 0; x < numIntegers; ++x)
    if (!elimination.eliminated(x)) {
      layout.integerZ[x] = layout.size++;
      integer_.push_back(1);
      ++integerUnknowns_;
    }

  // C: a copy is its fan's base (continuous, or integer combinations) turned, plus its integer shift.
  std::vector<Eigen::Triplet<double>> triplets;
  for (int32_t c = 0; c < numCopies; ++c) {
    const int32_t fan = cut.copyFan[c];
    ComboPoint base;
    if (baseCombo[2 * fan]) base.u = *baseCombo[2 * fan];
    if (baseCombo[2 * fan + 1]) base.v = *baseCombo[2 * fan + 1];
    const ComboPoint whole = added(turned(copyTurns[c], base), copyShift[c], 1);
    addRow(triplets, 2 * c, elimination.resolve(whole.u), layout);
    addRow(triplets, 2 * c + 1, elimination.resolve(whole.v), layout);
    for (int i = 0; i < 2; ++i) {
      const auto [j, sign] = turnedComponent(copyTurns[c], i);
      const int32_t column = layout.baseColumn[2 * fan + j];
      if (column >= 0) triplets.emplace_back(2 * c + i, column, static_cast<double>(sign));
    }
  }
  C_.resize(2 * numCopies, layout.size);
  C_.setFromTriplets(triplets.begin(), triplets.end());
  triplets.clear();
  for (int32_t e = 0; e < t.numEdges; ++e)
    if (cutIndex[e] >= 0)
      for (int k = 0; k < 2; ++k)
        addRow(triplets, 2 * e + k, elimination.resolve({{2 * cutIndex[e] + k, 1}}), layout);
  shift_.resize(2 * t.numEdges, layout.size);
  shift_.setFromTriplets(triplets.begin(), triplets.end());

  // A component with no iso-edge can move as a whole: one of its regular bases is pinned off the grid (with
  // cones, this is what was measured; leaving it free too was within noise: homer 0 -> 1 flipped quads,
  // fandisk 43 -> 38 irregular vertices). One with iso-edges is placed by their integer lines: a pin there
  // would hold a vertex off its place, so none is set, and the rounding's ridge (greedy_rounding.cpp) takes
  // what freedom is left (a cylinder between two boundary loops slides round its axis).
  std::vector<uint8_t> anchored(t.components.size(), 0), componentPinned(t.components.size(), 0);
  for (const CrossFieldCut::IsoEdge& iso : cut.isoEdges) anchored[t.faceComponent[iso.face]] = 1;
  for (int32_t fan = 0; fan < numFans; ++fan) {
    const int32_t component = t.vertexComponent[cut.fanVertex[fan]];
    const int32_t bu = layout.baseColumn[2 * fan], bv = layout.baseColumn[2 * fan + 1];
    if (component < 0 || anchored[component] || componentPinned[component] || bu < 0 || bv < 0) continue;
    componentPinned[component] = 1;
    pinned_.emplace_back(bu, 0.3125);
    pinned_.emplace_back(bv, 0.6875);
  }
}

SeamlessParametrization SeamlessSystem::solve(const SurfaceMesh& mesh, const MeshGeometry& g, double h,
                                              const std::vector<double>& faceWeight,
                                              const std::vector<double>& keptIntegers,
                                              const ParametrizationProgress& progress) const {
  SeamlessParametrization out;
  // The least-squares energy sum_f A_f (|grad u - X/h|^2 + |grad v - Y/h|^2) over the copies' coordinates
  // (w^T L w - 2 b_w^T w), then through w = C z onto the unknowns: K = C^T L C. The rows of C next to the
  // cut's trunk sum many integer unknowns; the product keeps that to the matrix, not the faces' terms.
  const int32_t numCopies = static_cast<int32_t>(C_.rows() / 2);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd bw = Eigen::VectorXd::Zero(2 * numCopies);
  for (int32_t f = 0; f < t_.numFaces; ++f) {
    Eigen::Vector3d p[3], grad[3];
    facePositions(mesh, f, p);
    const double area = g.faceArea[f] * (faceWeight.empty() ? 1.0 : faceWeight[f]);
    if (!(area > 0)) continue;
    barycentricGradients(p, grad);
    const Eigen::Vector3d n(&g.faceNormal[3 * f]), x(&cut_.direction[3 * f]);
    const Eigen::Vector3d target[2] = {x / h, n.cross(x) / h};
    for (int comp = 0; comp < 2; ++comp)
      for (int j = 0; j < 3; ++j) {
        const int32_t wj = 2 * cut_.cornerCopy[3 * f + j] + comp;
        bw[wj] += area * grad[j].dot(target[comp]);
        for (int k = 0; k < 3; ++k)
          triplets.emplace_back(wj, 2 * cut_.cornerCopy[3 * f + k] + comp, area * grad[j].dot(grad[k]));
      }
  }
  SparseMatrix L(2 * numCopies, 2 * numCopies);
  L.setFromTriplets(triplets.begin(), triplets.end());
  triplets = {};
  const SparseMatrix K = SparseMatrix(C_.transpose()) * (L * C_);
  const Eigen::VectorXd b = C_.transpose() * bw;

  std::vector<std::pair<int32_t, double>> pinned = pinned_;
  if (!keptIntegers.empty()) {
    std::size_t k = 0;
    for (int32_t i = 0; i < static_cast<int32_t>(integer_.size()); ++i)
      if (integer_[i]) pinned.emplace_back(i, keptIntegers.at(k++));
  }
  bool stopped = false;
  const GreedyRounding rounded = roundGreedily(K, b, integer_, pinned, [&](double fraction) {
    stopped = progress && !progress(fraction);
    return !stopped;
  });
  if (stopped) return out;
  if (!rounded.ok)
    throw InputError("quad mesh: the parametrization's system could not be solved (a degenerate mesh?)");
  const Eigen::VectorXd& z = rounded.z;
  out.roundingSteps = rounded.roundingSteps;
  for (int32_t i = 0; i < static_cast<int32_t>(integer_.size()); ++i)
    if (integer_[i]) out.integers.push_back(z[i]);

  Eigen::VectorXd w = C_ * z;
  const Eigen::VectorXd shift = shift_ * z;
  // A regular tessellation meets the grid exactly (a vertex on a grid point, an edge along a grid line) up to
  // round-off: snapped, such places are exact, and the extraction's tests of them (a zero barycentric, a
  // vertex with both coordinates whole) hold on every side alike. The transitions are whole turns and shifts,
  // so the copies of a point snap alike.
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (std::abs(w[i] - std::round(w[i])) < 1e-9) w[i] = std::round(w[i]);
  out.cornerUV.resize(6 * t_.numFaces);
  for (int32_t f = 0; f < t_.numFaces; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int32_t c = cut_.cornerCopy[3 * f + k];
      out.cornerUV[6 * f + 2 * k] = w[2 * c];
      out.cornerUV[6 * f + 2 * k + 1] = w[2 * c + 1];
    }
    if (!(uvTwiceArea(out.cornerUV, f) > 0)) ++out.flippedFaces;
  }
  out.edgeShift.assign(shift.data(), shift.data() + shift.size());
  return out;
}

}  // namespace tvf
